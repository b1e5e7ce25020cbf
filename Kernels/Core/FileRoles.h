// The files one command reads and writes, checked against each other before any work: an
// output never replaces an input, another output, or either one's sidecar.
#pragma once

#include <string>
#include <vector>

namespace tsynth
{

class FileRoles
{
public:
  // A file the command reads, named as the user gave it to it ("the exemplar", "--guide").
  // With `sidecar`, its NAME.json (sidecarPathFor) is read too, if it exists.
  void input(const std::string& path, const std::string& role, bool sidecar = true);
  // What an output holds: heights (a .png brings its NAME.json sidecar), or anything else (a
  // picture, a feature tree, a report) written alone.
  enum class Content
  {
    Heights,
    // Heights whose NAME.json sidecar this command writes too (tiles): the
    // sidecar is an output, and one left there by an earlier run is replaced.
    HeightsAndSidecar,
    Other
  };
  // A file the command writes ("-o", "--flow").
  void output(const std::string& path, const std::string& role, Content content = Content::Heights);
  // Throws tsynth::Error, one sentence naming both roles, if an output is the same file as an
  // input or as another output (resolved: symlinks, "..", hard links by device and inode),
  // sidecars included; if an output exists and is a folder, device, pipe or socket; or if an
  // output GeoTIFF has a NAME.json beside it, or another output written there, that readers
  // would take for its sidecar.
  void check() const;

private:
  struct Entry
  {
    std::string path;
    std::string role;
  };
  // An output GeoTIFF with a NAME.json beside it that is not its own: readers would apply it.
  struct Stray
  {
    std::string path;
    std::string sidecar;
    std::string description;
  };
  std::vector<Stray> strays_;
  // Where readers look for the sidecar of an output GeoTIFF (NAME.json): no other output there.
  std::vector<Entry> sidecarSpots_;
  std::vector<Entry> inputs_;
  std::vector<Entry> outputs_;
};

} // namespace tsynth
