// Writing a file so that it appears complete or not at all: write to a hidden
// temporary beside the target, then rename over it.
#pragma once

#include <string>

namespace tsynth
{

// Throws tsynth::Error, one sentence naming the path, unless a file can be
// written at `target`: its folder exists and is a folder, the target is not a
// folder, and a file can be created beside it (tried, then removed). Front ends
// call it before long work, so that a run never ends in an unwritable path.
void checkOutputPath(const std::string& target);

class OutputFile
{
public:
  // Throws tsynth::Error as checkOutputPath does.
  explicit OutputFile(std::string target);
  // Removes the temporary if commit() was not reached (an error on the way).
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Where the writer should write.
  const std::string& temporaryPath() const { return temporary_; }
  const std::string& target() const { return target_; }
  // Renames the temporary onto the target. Throws tsynth::Error on failure.
  void commit();

  // Removes the temporaries of every OutputFile alive now. Async-signal-safe (only unlink), so
  // a signal handler can call it before the process dies: a killed command leaves no partial
  // file behind.
  static void removeLiveTemporaries();

private:
  std::string target_;
  std::string temporary_;
  bool committed_ = false;
  int slot_ = -1; // this temporary's place in the live list, -1 if it did not fit
};

} // namespace tsynth
