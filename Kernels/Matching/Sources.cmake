set(TSYNTH_MATCHING_SOURCES
  Matching/CandidatePool.cxx
  Matching/DenseSearch.cxx
  Matching/FeatureCost.cxx
  Matching/NoiseVariance.cxx
  Matching/Orientation.cxx)
