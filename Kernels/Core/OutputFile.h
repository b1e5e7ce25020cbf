// Writing a file so that it appears complete or not at all: write to a hidden
// temporary beside the target, then rename over it.
#pragma once

#include <string>

namespace tsynth
{

class OutputFile
{
public:
  // Throws tsynth::Error if the target's folder does not exist.
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

private:
  std::string target_;
  std::string temporary_;
  bool committed_ = false;
};

} // namespace tsynth
