#include "XmlDataFiles.h"

#include "VtkErrorObserver.h"

#include "Core/Error.h"
#include "Core/OutputFile.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkSetGet.h>
#include <vtkStringOutputWindow.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLReader.h>
#include <vtkXMLWriter.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tsynth
{
namespace
{

// While it lives, VTK prints no error or warning: those of objects with an error observer reach
// the observer, the others (a reader's data compressor) are kept in text() instead of printed.
class QuietVtk
{
public:
  QuietVtk()
    : previous_(vtkOutputWindow::GetInstance())
    , display_(vtkObject::GetGlobalWarningDisplay())
    , stderrLevel_(vtkLogger::GetCurrentVerbosityCutoff())
  {
    previous_->Register(nullptr);
    vtkOutputWindow::SetInstance(capture_);
    vtkObject::GlobalWarningDisplayOn();
    // VTK 9 also logs each unobserved error to stderr through vtkLogger.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~QuietVtk()
  {
    vtkLogger::SetStderrVerbosity(stderrLevel_);
    vtkObject::SetGlobalWarningDisplay(display_);
    vtkOutputWindow::SetInstance(previous_);
    previous_->UnRegister(nullptr);
  }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;
  std::string text() const { return capture_->GetOutput(); }

private:
  vtkNew<vtkStringOutputWindow> capture_;
  vtkOutputWindow* previous_;
  int display_;
  vtkLogger::Verbosity stderrLevel_;
};

vtkIdType countAttribute(vtkXMLDataElement* piece, const char* name)
{
  vtkIdType n = 0;
  return piece->GetScalarAttribute(name, n) != 0 && n > 0 ? n : 0;
}

// Points and cells of a piece: unstructured counts, or an image's extent.
std::array<vtkIdType, 2> pieceSize(vtkXMLDataElement* piece)
{
  std::array<int, 6> e{};
  if (piece->GetVectorAttribute("Extent", 6, e.data()) == 6)
  {
    vtkIdType points = 1;
    vtkIdType cells = 1;
    for (int d = 0; d < 3; ++d)
    {
      const vtkIdType span = e[2 * d + 1] - e[2 * d];
      points *= span >= 0 ? span + 1 : 0;
      cells *= span > 0 ? span : 1;
    }
    return { points, cells };
  }
  const vtkIdType cells = countAttribute(piece, "NumberOfVerts") +
    countAttribute(piece, "NumberOfLines") + countAttribute(piece, "NumberOfStrips") +
    countAttribute(piece, "NumberOfPolys") + countAttribute(piece, "NumberOfCells");
  return { countAttribute(piece, "NumberOfPoints"), cells };
}

// Reads up to `wanted` values of a DataArray element into `buffer` (resized to
// fit them in the array's own type, returned in `type`); returns how many the
// file holds, or 0 for an element without a type.
std::size_t readValues(vtkXMLDataParser* parser,
  vtkXMLDataElement* array,
  std::size_t wanted,
  std::vector<char>& buffer,
  int& type)
{
  if (array->GetWordTypeAttribute("type", type) == 0)
  {
    return 0;
  }
  const int size = vtkDataArray::GetDataTypeSize(type);
  if (size <= 0 || wanted == 0)
  {
    return wanted;
  }
  buffer.assign(wanted * static_cast<std::size_t>(size), 0);
  const char* format = array->GetAttribute("format");
  if (format != nullptr && std::strcmp(format, "appended") == 0)
  {
    vtkTypeInt64 offset = 0;
    if (array->GetScalarAttribute("offset", offset) == 0)
    {
      return 0;
    }
    return parser->ReadAppendedData(offset, buffer.data(), 0, wanted, type);
  }
  const int ascii = format != nullptr && std::strcmp(format, "ascii") == 0 ? 1 : 0;
  return parser->ReadInlineData(array, ascii, buffer.data(), 0, wanted, type);
}

// The values the parser finds for a DataArray element, up to `wanted`.
std::size_t valuesFound(vtkXMLDataParser* parser, vtkXMLDataElement* array, std::size_t wanted)
{
  std::vector<char> buffer;
  int type = 0;
  return readValues(parser, array, wanted, buffer, type);
}

// Up to `wanted` values of a DataArray element as 64-bit integers.
std::vector<long long> integersFound(vtkXMLDataParser* parser,
  vtkXMLDataElement* array,
  std::size_t wanted)
{
  std::vector<char> buffer;
  int type = 0;
  const std::size_t found = readValues(parser, array, wanted, buffer, type);
  std::vector<long long> values(std::min(found, wanted));
  if (buffer.empty())
  {
    values.clear();
    return values;
  }
  switch (type)
  {
    vtkTemplateMacro(for (std::size_t k = 0; k < values.size(); ++k) {
      values[k] = static_cast<long long>(reinterpret_cast<const VTK_TT*>(buffer.data())[k]);
    });
    default:
      values.clear();
  }
  return values;
}

// The most values a file of `fileBytes` bytes can hold: 8 per byte (bit
// arrays) times the most its compressor expands data: zlib about 1032-fold,
// LZ4 255-fold; LZMA has no such bound (infinity: nothing is refused).
double valueCapacity(vtkXMLDataElement* root, long long fileBytes)
{
  constexpr double kValuesPerByte = 8.0;
  const char* compressor = root->GetAttribute("compressor");
  double expansion = 1.0;
  if (compressor != nullptr && std::strcmp(compressor, "vtkZLibDataCompressor") == 0)
  {
    expansion = 1032.0;
  }
  else if (compressor != nullptr && std::strcmp(compressor, "vtkLZ4DataCompressor") == 0)
  {
    expansion = 255.0;
  }
  else if (compressor != nullptr && compressor[0] != '\0')
  {
    return std::numeric_limits<double>::infinity();
  }
  return kValuesPerByte * expansion * static_cast<double>(fileBytes);
}

// Throws tsynth::Error if `values` values (what they are: `claim`) would need
// a large buffer and cannot fit in the file (`capacity`, valueCapacity):
// nothing is allocated for such a claim. Small claims are read and compared
// with what the file holds, which gives the more telling sentence.
void checkClaim(double values, double capacity, const std::string& path, const std::string& claim)
{
  constexpr double kLargeClaim = 1 << 21; // values: 16 MB as 64-bit numbers
  if (values > kLargeClaim && values > capacity)
  {
    throw Error(path + " is damaged: it claims " + claim + ", more than a file of its size holds.");
  }
}

// Throws tsynth::Error unless the cells of one kind (Verts, Lines, Strips,
// Polys) have `cells` offsets that never fall and a connectivity array with
// as many point ids as the last offset says.
void checkCells(vtkXMLDataParser* parser,
  vtkXMLDataElement* piece,
  const char* kind,
  double capacity,
  const std::string& path)
{
  const vtkIdType cells = countAttribute(piece, (std::string("NumberOf") + kind).c_str());
  if (cells == 0)
  {
    return;
  }
  checkClaim(static_cast<double>(cells), capacity, path, std::to_string(cells) + " " + kind);
  const std::string damaged = path + " is damaged: its " + kind + " ";
  vtkXMLDataElement* element = piece->FindNestedElementWithName(kind);
  vtkXMLDataElement* offsets = element != nullptr
    ? element->FindNestedElementWithNameAndAttribute("DataArray", "Name", "offsets")
    : nullptr;
  vtkXMLDataElement* connectivity = element != nullptr
    ? element->FindNestedElementWithNameAndAttribute("DataArray", "Name", "connectivity")
    : nullptr;
  if (offsets == nullptr || connectivity == nullptr)
  {
    throw Error(damaged + "lack their offsets or connectivity array.");
  }
  // Older files give one end offset per cell, newer ones a leading 0 too.
  const std::vector<long long> ends =
    integersFound(parser, offsets, static_cast<std::size_t>(cells) + 1);
  if (ends.size() < static_cast<std::size_t>(cells))
  {
    throw Error(
      damaged + "offsets hold fewer values than their " + std::to_string(cells) + " cells need.");
  }
  long long previous = 0;
  for (long long end : ends)
  {
    if (end < previous)
    {
      throw Error(damaged + "offsets fall or are negative (" + std::to_string(end) + ").");
    }
    previous = end;
  }
  if (static_cast<double>(previous) > capacity ||
    valuesFound(parser, connectivity, static_cast<std::size_t>(previous)) <
      static_cast<std::size_t>(previous))
  {
    throw Error(damaged + "connectivity holds fewer point ids than their offsets say (" +
      std::to_string(previous) + ").");
  }
}

// Throws tsynth::Error for the first array of `group` (PointData, CellData,
// Points) with fewer than `tuples` tuples.
void checkGroup(vtkXMLDataParser* parser,
  vtkXMLDataElement* group,
  vtkIdType tuples,
  double capacity,
  const std::string& path,
  const char* of)
{
  for (int k = 0; group != nullptr && k < group->GetNumberOfNestedElements(); ++k)
  {
    vtkXMLDataElement* array = group->GetNestedElement(k);
    if (std::strcmp(array->GetName(), "DataArray") != 0)
    {
      continue;
    }
    int components = 1;
    array->GetScalarAttribute("NumberOfComponents", components);
    const double claimed = static_cast<double>(tuples) * std::max(1, components);
    checkClaim(claimed, capacity, path, std::to_string(tuples) + " " + of);
    const std::size_t wanted = static_cast<std::size_t>(claimed);
    if (valuesFound(parser, array, wanted) < wanted)
    {
      const char* name = array->GetAttribute("Name");
      throw Error(path + " is damaged: its " + (name != nullptr ? name : "unnamed") +
        " array holds fewer values than its " + std::to_string(tuples) + " " + of + " need.");
    }
  }
}

void checkArrayLengths(vtkXMLReader* reader, const std::string& path, const std::string& refusal)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser != nullptr ? parser->GetRootElement() : nullptr;
  // The reader closed its stream after the information pass; the parser's
  // recorded data positions are offsets into the file.
  std::ifstream stream(path, std::ios::in | std::ios::binary);
  if (root == nullptr || !stream)
  {
    throw Error(refusal);
  }
  stream.seekg(0, std::ios::end);
  const double capacity = valueCapacity(root, static_cast<long long>(stream.tellg()));
  stream.seekg(0, std::ios::beg);
  std::istream* previous = parser->GetStream();
  parser->SetStream(&stream);
  struct Restore
  {
    vtkXMLDataParser* parser;
    std::istream* stream;
    ~Restore() { parser->SetStream(stream); }
  } restore{ parser, previous };
  vtkXMLDataElement* dataset = root != nullptr ? root->GetNestedElement(0) : nullptr;
  for (int p = 0; dataset != nullptr && p < dataset->GetNumberOfNestedElements(); ++p)
  {
    vtkXMLDataElement* piece = dataset->GetNestedElement(p);
    if (std::strcmp(piece->GetName(), "Piece") != 0)
    {
      continue;
    }
    const std::array<vtkIdType, 2> size = pieceSize(piece);
    checkGroup(
      parser, piece->FindNestedElementWithName("Points"), size[0], capacity, path, "points");
    checkGroup(
      parser, piece->FindNestedElementWithName("PointData"), size[0], capacity, path, "points");
    checkGroup(
      parser, piece->FindNestedElementWithName("CellData"), size[1], capacity, path, "cells");
    for (const char* kind : { "Verts", "Lines", "Strips", "Polys" })
    {
      checkCells(parser, piece, kind, capacity, path);
    }
  }
}

} // namespace

// VTK reads an image's Spacing or Origin it cannot parse ("nan", "1e999") as its default (1 m
// cells at 0): each of the three numbers must be finite, and the spacing not zero.
void checkImageFrame(vtkXMLReader* reader, const std::string& path)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser != nullptr ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* image =
    root != nullptr ? root->FindNestedElementWithName("ImageData") : nullptr;
  if (image == nullptr)
  {
    return;
  }
  for (const char* name : { "Spacing", "Origin" })
  {
    const char* text = image->GetAttribute(name);
    if (text == nullptr)
    {
      continue;
    }
    std::istringstream tokens(text);
    std::string token;
    int count = 0;
    while (tokens >> token)
    {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      const bool zeroSpacing = std::string(name) == "Spacing" && v == 0.0;
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v) || zeroSpacing)
      {
        throw Error(path + " has " + name + " \"" + text + "\": the image's " +
          (std::string(name) == "Spacing" ? "cell size" : "origin") +
          " must be three finite numbers" +
          (std::string(name) == "Spacing" ? ", none of them zero." : "."));
      }
      ++count;
    }
    if (count != 3)
    {
      throw Error(
        path + " has " + name + " \"" + text + "\"; an image's " + name + " is three numbers.");
    }
  }
}

void readXmlDataFile(vtkXMLReader* reader, const std::string& path, const std::string& what)
{
  const QuietVtk quiet;
  VtkErrorObserver observer;
  reader->AddObserver(vtkCommand::ErrorEvent, observer.callback);
  reader->SetParserErrorObserver(observer.callback);
  const std::string refusal = path + " is not a VTK " + what + " file that can be read.";
  reader->UpdateInformation();
  if (observer.failed)
  {
    throw Error(refusal);
  }
  checkImageFrame(reader, path);
  // A block that does not decompress is reported by the parser's compressor alone (VTK then
  // reads on with the array missing), in the captured text: named as damage.
  const auto damaged = [&] { return quiet.text().find("uncompress") != std::string::npos; };
  if (damaged())
  {
    throw Error(path + " is damaged: some of its compressed data does not decompress.");
  }
  // VTK's parser sizes its buffers from the headers it reads: a header it
  // decodes to an absurd size ends in std::length_error or std::bad_alloc.
  try
  {
    checkArrayLengths(reader, path, refusal);
    reader->Update();
  }
  catch (const std::length_error&)
  {
    throw Error(path + " is damaged: an array's header claims more data than any file holds.");
  }
  catch (const std::bad_alloc&)
  {
    throw Error("Reading " + path +
      " needs more memory than this machine has: its array headers are probably damaged.");
  }
  if (damaged())
  {
    throw Error(path + " is damaged: some of its compressed data does not decompress.");
  }
  if (observer.failed || reader->GetOutputDataObject(0) == nullptr)
  {
    throw Error(refusal);
  }
}

void writeXmlDataFile(vtkXMLWriter* writer, vtkDataObject* data, const std::string& path)
{
  OutputFile file(path);
  // Into memory first: VTK 9.2's poly-data writer frees unset arrays (a crash) when a write
  // to disk fails mid-piece, and its executive prints to the terminal. The bytes are then
  // written with every write checked.
  VtkErrorObserver catcher;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher.callback);
  writer->SetInputData(data);
  writer->WriteToOutputStringOn();
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  const int written = writer->Write();
  const unsigned long code = writer->GetErrorCode();
  writer->RemoveObserver(catcher.callback);
  if (written == 0 || code != vtkErrorCode::NoError || catcher.failed)
  {
    throw Error("Cannot write " + path +
      (code != vtkErrorCode::NoError
          ? std::string(": ") + vtkErrorCode::GetStringFromErrorCode(code) + "."
          : std::string(".")));
  }
  file.write(writer->GetOutputString());
  file.commit();
}

} // namespace tsynth
