#include "FileRoles.h"

#include "Error.h"
#include "HeightfieldIO.h"
#include "OutputFile.h"
#include "Sidecar.h"

#include <filesystem>
#include <optional>
#include <sys/stat.h>

namespace fs = std::filesystem;

namespace tsynth
{

namespace
{

bool isPng(const std::string& path)
{
  return hasExtension(path, ".png");
}

// A raster written without a sidecar that readers still look for one beside (GeoTIFF).
bool readsSidecarWithoutOne(const std::string& path)
{
  const std::string ext = lowerExtension(path);
  return ext == ".tif" || ext == ".tiff";
}

// A file's identity: device and inode when it exists (hard links and symlinks meet there),
// otherwise its resolved path.
struct Identity
{
  std::optional<std::pair<dev_t, ino_t>> inode;
  std::string resolved;

  bool operator==(const Identity& o) const
  {
    if (inode && o.inode)
    {
      return *inode == *o.inode;
    }
    return resolved == o.resolved;
  }
};

Identity identityOf(const std::string& path)
{
  Identity id;
  struct stat st
  {
  };
  if (::stat(path.c_str(), &st) == 0)
  {
    id.inode = std::make_pair(st.st_dev, st.st_ino);
  }
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
  id.resolved = ec ? path : resolved.string();
  return id;
}

struct Named
{
  std::string path;
  std::string description; // "-o out.png" or "the sidecar out.json of -o out.png"
  Identity id;
};

std::string describe(const std::string& role, const std::string& path)
{
  return role + " " + path;
}

} // namespace

void FileRoles::input(const std::string& path, const std::string& role, bool sidecar)
{
  inputs_.push_back({ path, role });
  const std::string side = sidecarPathFor(path);
  std::error_code ec;
  if (sidecar && side != path && fs::exists(side, ec))
  {
    inputs_.push_back({ side, "the sidecar of " + describe(role, path) });
  }
}

void FileRoles::output(const std::string& path, const std::string& role, Content content)
{
  outputs_.push_back({ path, role });
  const std::string side = sidecarPathFor(path);
  if (content == Content::HeightsAndSidecar)
  {
    outputs_.push_back({ side, "the sidecar of " + describe(role, path) });
    return;
  }
  if (content == Content::Heights && isPng(path))
  {
    outputs_.push_back({ side, "the sidecar of " + describe(role, path) });
  }
  std::error_code ec;
  if (readsSidecarWithoutOne(path) && side != path)
  {
    if (fs::exists(side, ec))
    {
      strays_.push_back({ path, side, describe(role, path) });
    }
    sidecarSpots_.push_back({ side, describe(role, path) });
  }
}

void FileRoles::check() const
{
  if (!strays_.empty())
  {
    const Stray& s = strays_.front();
    throw Error("Cannot write " + s.description + ": " + s.sidecar +
      " beside it would be read as its sidecar and change its heights or cell size; move " +
      s.sidecar + " away or give the output another name.");
  }
  std::vector<Named> inputs;
  for (const Entry& e : inputs_)
  {
    inputs.push_back({ e.path, describe(e.role, e.path), identityOf(e.path) });
  }
  std::vector<Named> outputs;
  for (const Entry& e : outputs_)
  {
    checkOutputPath(e.path);
    outputs.push_back({ e.path, describe(e.role, e.path), identityOf(e.path) });
  }
  for (const Entry& spot : sidecarSpots_)
  {
    const Identity id = identityOf(spot.path);
    for (const Named& out : outputs)
    {
      if (out.id == id)
      {
        throw Error("Cannot write " + out.description + ": readers of " + spot.role +
          " would take it for that terrain's sidecar; give it another name.");
      }
    }
  }
  for (std::size_t o = 0; o < outputs.size(); ++o)
  {
    for (const Named& in : inputs)
    {
      if (outputs[o].id == in.id)
      {
        throw Error("Cannot write " + outputs[o].description + ": it is the same file as " +
          in.description + ", which would be lost; give the output another name.");
      }
    }
    for (std::size_t other = 0; other < o; ++other)
    {
      if (outputs[o].id == outputs[other].id)
      {
        throw Error("Cannot write " + outputs[o].description + ": it is the same file as " +
          outputs[other].description +
          ", and one would replace the other; give them different "
          "names.");
      }
    }
  }
}

} // namespace tsynth
