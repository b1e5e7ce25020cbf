#include "PropertyEnums.h"

#include "Synthesis/SynthesisRequest.h"

namespace tsynth
{

// Each property's values are its kernel enumeration's, in the order of its words
// (Core/OptionTable.h); a value without a word fails the request.

Backend backendFromProperty(int value)
{
  return choiceOf<Backend>(choicesOf(kBackendWords), value, "Backend");
}

MergeMode mergeModeFromProperty(int value)
{
  return choiceOf<MergeMode>(choicesOf(kMergeModeWords), value, "Merge mode");
}

FillOrder fillOrderFromProperty(int value)
{
  return choiceOf<FillOrder>(choicesOf(kFillOrderWords), value, "Fill order");
}

PitRemovalMethod pitRemovalMethodFromProperty(int value)
{
  return choiceOf<PitRemovalMethod>(choicesOf(kPitRemovalMethodWords), value, "Method");
}

std::optional<PitRemovalMethod> drainageFromProperty(int value)
{
  return offOrMethod(value);
}

} // namespace tsynth
