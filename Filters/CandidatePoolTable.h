// The candidate pool as a vtkTable and back, exactly: the Terrain Candidate
// Builder writes it, and the Terrain Patch Matcher reads it (its Candidate Pool
// input) instead of building the pool again, so the two stages chain.
// One row per candidate variant. Columns: Exemplar, Site, Variant, Kind,
// FeatureType, Arms (integers); CellX, CellY (the centre in the exemplar's
// cells); Angle0..3 (arm directions as placed, degrees, NaN past the arms);
// Noise (kNoiseLevels band-pass variances, m^2), Along and Across (the arms'
// height profiles, m), Descriptor (the overlap summary, m) and Landform (the
// landform samples, m) as multi-component columns; X and Y (the centre in
// metres, for plotting; not read back). Field data: PatchSize, HeightScale,
// and per exemplar ExemplarWidth, ExemplarHeight and ExemplarChecksum (a hash
// of the heights the pool was cut from, so a pool is never used with others).
#pragma once

#include "Matching/CandidatePool.h"

class vtkTable;

namespace tsynth
{

struct ExemplarInputs;

// Fills `table` (emptied first) with the pool built from `in`'s exemplars.
void writePoolTable(const CandidatePool& pool, const ExemplarInputs& in, vtkTable* table);

// The pool a table written by writePoolTable holds, exemplar checksums
// included, for checkGivenPool against the exemplars it is used with. Throws
// tsynth::Error with one sentence naming what is missing or misshapen.
CandidatePool poolFromTable(vtkTable* table);

} // namespace tsynth
