// The values the matcher's options may take in a front end (the Patch Matcher
// filter): light enough for the filter's header, whose clamp macros take them;
// the options table (matcherOptionRows, PatchMatcher.h) gives them to it and to
// the plugin XML's check.
#pragma once

namespace tsynth
{

constexpr int kMaxCandidatesKept = 1000;  // K: more is a table nobody reads
constexpr double kMaxMatchWeight = 1.0e6; // a cost weight beyond it drowns every other term

} // namespace tsynth
