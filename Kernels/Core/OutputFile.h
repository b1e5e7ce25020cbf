// Writing files so that they appear complete or not at all: each is written to a short
// hidden temporary beside its target, checked (every write, then fsync and close), and
// renamed over the target; inside a Publication the renames wait until the whole command
// has succeeded, so a command's outputs appear together or not at all.
#pragma once

#include <string>

namespace tsynth
{

// Throws tsynth::Error, one sentence naming the path, unless a file can be
// written at `target`: its folder exists and is a folder, the target is not a
// folder, device, pipe or socket, and a file can be created beside it (tried, then
// removed). Front ends call it before long work, so that a run never ends in an
// unwritable path.
void checkOutputPath(const std::string& target);

class OutputFile
{
public:
  // Throws tsynth::Error as checkOutputPath does, and if another OutputFile of the open
  // Publication already writes `target`.
  explicit OutputFile(std::string target);
  // Removes the temporary if commit() was not reached (an error on the way).
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Where the writer should write: a short name (".tsynth-PID-N.tmp.EXT") in the target's
  // folder, so a target name of any legal length has a legal temporary.
  const std::string& temporaryPath() const { return temporary_; }
  const std::string& target() const { return target_; }
  // Writes `bytes` as the whole temporary, checking every write. Throws tsynth::Error naming
  // the target ("the disk is full") on failure.
  void write(const std::string& bytes);
  // Checks the temporary (it exists, is not empty, and fsync and close succeed: a full disk
  // or quota shows here at the latest), then renames it onto the target, or, while a
  // Publication is open, hands it to the Publication. Throws tsynth::Error naming the
  // target on failure.
  void commit();

  // Removes the temporaries of every OutputFile alive now and of the open Publication.
  // Async-signal-safe (only unlink), so a signal handler can call it before the process dies:
  // a killed command leaves no partial file behind.
  static void removeLiveTemporaries();

private:
  std::string target_;
  std::string temporary_;
  bool committed_ = false;
  int slot_ = -1; // this temporary's place in the live list, -1 if it did not fit
};

// The outputs of one command, published together. While one is open, OutputFile::commit()
// stages its file instead of renaming it; publish() renames them all with the terminating
// signals held, and a Publication destroyed unpublished removes every staged temporary (and
// the folders it was told it created, if they are left empty). One at a time per process.
// Publishes what the open Publication has staged so far, at once (as publish() does), and
// leaves it open for the rest: for an output meant to stay even if the command is stopped
// later (tsynth synth --preview, written before the long synthesis). Without an open
// Publication there is nothing staged and nothing to do.
void publishStagedOutputs();

// Creates the folder `path` and any missing parents (tsynth::Error, one sentence, if it
// cannot). While a Publication is open, the folders it creates are removed again, if left
// empty, when nothing is published.
void createOutputFolder(const std::string& path);

class Publication
{
public:
  Publication();
  ~Publication();
  Publication(const Publication&) = delete;
  Publication& operator=(const Publication&) = delete;

  // Renames every staged temporary onto its target. Throws tsynth::Error on the first failure
  // (the files not yet renamed are removed).
  void publish();
  // True while a Publication is open.
  static bool isOpen();
};

} // namespace tsynth
