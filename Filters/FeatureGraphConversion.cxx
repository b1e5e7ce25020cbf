#include "FeatureGraphConversion.h"

#include "Core/Constants.h"
#include "Core/Error.h"
#include "VtkErrorObserver.h"
#include "XmlDataFiles.h"

#include <vtkBase64Utilities.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tsynth
{
namespace
{

vtkNew<vtkIntArray> intArray(const char* name)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  return a;
}

} // namespace

void featureGraphToPolyData(const FeatureGraph& g, vtkPolyData* out, double ox, double oy)
{
  out->Initialize();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  auto kind = intArray("NodeKind");
  auto degree = intArray("Degree");
  auto rank = intArray("BFSRank");
  auto component = intArray("ComponentId");
  vtkNew<vtkFloatArray> elevation;
  elevation->SetName("Elevation");
  vtkNew<vtkFloatArray> constraint;
  constraint->SetName("ElevationConstraint");
  bool anyConstraint = false;
  for (const FeatureChain& c : g.chains)
  {
    anyConstraint = anyConstraint || !c.constraint.empty();
  }

  std::vector<int> rankOf(g.nodes.size(), -1);
  for (std::size_t r = 0; r < g.bfsOrder.size(); ++r)
  {
    rankOf[static_cast<std::size_t>(g.bfsOrder[r])] = static_cast<int>(r);
  }
  auto addPoint = [&](const Point2& p, int k, int d, int r, int comp, float z, float zc)
  {
    points->InsertNextPoint(ox + p.x * g.cellX, oy + p.y * g.cellY, 0.0);
    kind->InsertNextValue(k);
    degree->InsertNextValue(d);
    rank->InsertNextValue(r);
    component->InsertNextValue(comp);
    elevation->InsertNextValue(z);
    constraint->InsertNextValue(zc);
  };
  const float nan = std::nanf("");
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
  {
    const FeatureNode& node = g.nodes[n];
    addPoint(node.position,
      static_cast<int>(node.kind),
      node.degree,
      rankOf[n],
      node.component,
      node.elevation,
      nan);
  }
  // End and branch nodes are also vertex cells, so ParaView can draw them as dots
  // (Threshold on NodeKind keeps them); vertex cells come before lines in cell order.
  vtkNew<vtkCellArray> verts;
  auto type = intArray("FeatureType");
  auto chainId = intArray("ChainId");
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
  {
    const vtkIdType id = static_cast<vtkIdType>(n);
    verts->InsertNextCell(1, &id);
    type->InsertNextValue(static_cast<int>(g.nodes[n].type));
    chainId->InsertNextValue(-1);
  }
  vtkNew<vtkCellArray> lines;
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    const FeatureChain& ch = g.chains[c];
    const int comp = g.nodes[static_cast<std::size_t>(ch.from)].component;
    vtkNew<vtkIdList> ids;
    ids->InsertNextId(ch.from);
    for (std::size_t k = 1; k + 1 < ch.points.size(); ++k)
    {
      const float zc = k < ch.constraint.size() ? ch.constraint[k] : nan;
      addPoint(ch.points[k],
        static_cast<int>(NodeKind::Path),
        2,
        -1,
        comp,
        k < ch.elevation.size() ? ch.elevation[k] : nan,
        zc);
      ids->InsertNextId(points->GetNumberOfPoints() - 1);
    }
    ids->InsertNextId(ch.to);
    lines->InsertNextCell(ids);
    type->InsertNextValue(static_cast<int>(ch.type));
    chainId->InsertNextValue(static_cast<int>(c));
    // Node constraints come from their chains' end values.
    if (!ch.constraint.empty())
    {
      constraint->SetValue(ch.from, ch.constraint.front());
      constraint->SetValue(ch.to, ch.constraint.back());
    }
  }
  out->SetPoints(points);
  out->SetVerts(verts);
  out->SetLines(lines);
  out->GetPointData()->AddArray(kind);
  out->GetPointData()->AddArray(degree);
  out->GetPointData()->AddArray(elevation);
  out->GetPointData()->AddArray(rank);
  out->GetPointData()->AddArray(component);
  if (anyConstraint)
  {
    out->GetPointData()->AddArray(constraint);
  }
  // Shown, a tree is coloured by its cells' FeatureType (ridges red, valleys blue, by the
  // plugin's map): ParaView colours by the active point scalars first, so there are none.
  out->GetCellData()->SetScalars(type);
  out->GetCellData()->AddArray(chainId);
  vtkNew<vtkIdTypeArray> order;
  order->SetName("BFSOrder");
  for (int v : g.bfsOrder)
  {
    order->InsertNextValue(v);
  }
  out->GetFieldData()->AddArray(order);
  vtkNew<vtkDoubleArray> cell;
  cell->SetName("CellSize");
  cell->InsertNextValue(g.cellX);
  cell->InsertNextValue(g.cellY);
  out->GetFieldData()->AddArray(cell);
  // The grid the graph was found on, so the lines used as a sketch give an output
  // of the same extent (polyDataToPolylineSketch).
  vtkNew<vtkIntArray> grid;
  grid->SetName("GridSize");
  grid->InsertNextValue(g.width);
  grid->InsertNextValue(g.height);
  out->GetFieldData()->AddArray(grid);
}

void controlPointsToPolyData(const FeatureGraph& g, vtkPolyData* out, double ox, double oy)
{
  out->Initialize();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts;
  auto node = intArray("NodeId");
  auto chain = intArray("ChainId");
  auto reached = intArray("Reached");
  vtkNew<vtkFloatArray> angle;
  angle->SetName("AngleDeg");
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
  {
    for (const ControlPoint& cp : g.nodes[n].controls)
    {
      const vtkIdType id =
        points->InsertNextPoint(ox + cp.position.x * g.cellX, oy + cp.position.y * g.cellY, 0.0);
      verts->InsertNextCell(1, &id);
      node->InsertNextValue(static_cast<int>(n));
      chain->InsertNextValue(cp.chain);
      reached->InsertNextValue(cp.reached ? 1 : 0);
      angle->InsertNextValue(static_cast<float>(cp.angle * 180.0 / kPi));
    }
  }
  out->SetPoints(points);
  out->SetVerts(verts);
  out->GetPointData()->AddArray(node);
  out->GetPointData()->AddArray(chain);
  out->GetPointData()->AddArray(reached);
  out->GetPointData()->AddArray(angle);
}

std::vector<Polyline> polyDataToPolylines(const vtkPolyData* constInput,
  double cellX,
  double cellY,
  double ox,
  double oy,
  std::string* warning)
{
  auto* input = const_cast<vtkPolyData*>(constInput);
  std::vector<Polyline> out;
  vtkCellArray* lines = input->GetLines();
  if (lines == nullptr || lines->GetNumberOfCells() == 0)
  {
    return out;
  }
  vtkDataArray* type = input->GetCellData()->GetArray("FeatureType");
  vtkDataArray* elevation = input->GetPointData()->GetArray("Elevation");
  if (type == nullptr && warning != nullptr)
  {
    *warning = "The poly-lines have no FeatureType cell array; they are taken as ridges.";
  }
  if (type != nullptr && type->GetNumberOfTuples() != input->GetNumberOfCells())
  {
    throw Error("The FeatureType cell array has " + std::to_string(type->GetNumberOfTuples()) +
      " values for " + std::to_string(input->GetNumberOfCells()) + " cells: give one per cell.");
  }
  if (elevation != nullptr && elevation->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    throw Error("The Elevation point array has " + std::to_string(elevation->GetNumberOfTuples()) +
      " values for " + std::to_string(input->GetNumberOfPoints()) + " points: give one per point.");
  }
  // Cell ids of lines follow verts in vtkPolyData's numbering.
  const vtkIdType firstLine = input->GetNumberOfVerts();
  vtkIdType lineIndex = 0;
  vtkNew<vtkIdList> ids;
  for (lines->InitTraversal(); lines->GetNextCell(ids); ++lineIndex)
  {
    Polyline p;
    if (type != nullptr)
    {
      p.type =
        type->GetComponent(firstLine + lineIndex, 0) < 0 ? FeatureType::Valley : FeatureType::Ridge;
    }
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double x[3];
      input->GetPoint(ids->GetId(k), x);
      p.points.push_back({ (x[0] - ox) / cellX, (x[1] - oy) / cellY });
      if (elevation != nullptr)
      {
        p.elevation.push_back(static_cast<float>(elevation->GetComponent(ids->GetId(k), 0)));
      }
    }
    out.push_back(std::move(p));
  }
  return out;
}

PolylineSketch polyDataToPolylineSketch(const vtkPolyData* constInput, std::string* warning)
{
  auto* input = const_cast<vtkPolyData*>(constInput);
  PolylineSketch sketch;
  sketch.lines = polyDataToPolylines(input, 1.0, 1.0, 0.0, 0.0, warning);
  vtkDataArray* grid = input->GetFieldData()->GetArray("GridSize");
  vtkDataArray* cell = input->GetFieldData()->GetArray("CellSize");
  const bool framed = grid != nullptr && cell != nullptr && grid->GetNumberOfValues() == 2 &&
    cell->GetNumberOfValues() == 2;
  if (framed)
  {
    // Two values, as one tuple of two components or two tuples of one.
    auto value = [](vtkDataArray* a, vtkIdType k)
    {
      const int nc = a->GetNumberOfComponents();
      return a->GetComponent(k / nc, static_cast<int>(k % nc));
    };
    sketch.frameWidth = value(grid, 0) * value(cell, 0);
    sketch.frameHeight = value(grid, 1) * value(cell, 1);
  }
  return sketch;
}

namespace
{

// vtkXMLPolyDataReader does not check that the cells refer to existing points;
// a damaged file would make every reader of the points read past their end.
void checkPointIds(vtkPolyData* data, const std::string& path)
{
  const vtkIdType points = data->GetNumberOfPoints();
  vtkNew<vtkIdList> ids;
  for (vtkCellArray* cells :
    { data->GetVerts(), data->GetLines(), data->GetPolys(), data->GetStrips() })
  {
    if (cells == nullptr)
    {
      continue;
    }
    for (cells->InitTraversal(); cells->GetNextCell(ids);)
    {
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        const vtkIdType id = ids->GetId(k);
        if (id < 0 || id >= points)
        {
          throw Error(path + " is damaged: a cell refers to point " + std::to_string(id) +
            " but the file has " + std::to_string(points) + " points.");
        }
      }
    }
  }
}

// Every DataArray element of an XML tree.
std::vector<vtkXMLDataElement*> dataArrays(vtkXMLDataElement* root)
{
  std::vector<vtkXMLDataElement*> arrays;
  std::vector<vtkXMLDataElement*> pending{ root };
  while (!pending.empty())
  {
    vtkXMLDataElement* e = pending.back();
    pending.pop_back();
    if (std::string(e->GetName()) == "DataArray")
    {
      arrays.push_back(e);
    }
    for (int k = 0; k < e->GetNumberOfNestedElements(); ++k)
    {
      pending.push_back(e->GetNestedElement(k));
    }
  }
  return arrays;
}

std::string arrayName(vtkXMLDataElement* array)
{
  const char* name = array->GetAttribute("Name");
  return name != nullptr ? name : "without a name";
}

std::string attribute(vtkXMLDataElement* e, const char* name)
{
  const char* value = e->GetAttribute(name);
  return value != nullptr ? value : "";
}

// More components than any array a VTK file holds (1 for scalars, 3 for points,
// 9 for tensors): vtkXMLReader loops over the components of each array it
// creates, and a damaged NumberOfComponents="3333333333" kept it busy for minutes.
constexpr long long kMaxArrayComponents = 1024;

// Every data array's NumberOfComponents, if given, is a whole number from 1 to
// kMaxArrayComponents.
void checkComponentCounts(const std::vector<vtkXMLDataElement*>& arrays, const std::string& path)
{
  for (vtkXMLDataElement* a : arrays)
  {
    const char* text = a->GetAttribute("NumberOfComponents");
    if (text == nullptr)
    {
      continue;
    }
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || n < 1 || n > kMaxArrayComponents)
    {
      throw Error(path + " is damaged: its data array " + arrayName(a) + " has " + text +
        " components (1 to " + std::to_string(kMaxArrayComponents) + " can be read).");
    }
  }
}

// Every data array must name a type VTK knows: vtkXMLReader (VTK 9.2)
// dereferences a null array when a FieldData array's type is missing or
// unknown (type="Float82"), and the process dies before any error is reported.
void checkArrayTypes(const std::vector<vtkXMLDataElement*>& arrays, const std::string& path)
{
  for (vtkXMLDataElement* a : arrays)
  {
    int type = 0;
    if (a->GetWordTypeAttribute("type", type) == 0)
    {
      throw Error(path + " is damaged: its data array " + arrayName(a) + " has no type VTK knows.");
    }
  }
}

// How a file stores the headers of its compressed arrays.
struct HeaderFormat
{
  int wordSize = 4; // header_type UInt32 (8: UInt64)
  bool bigEndian = false;
};

// Up to `count` header words from `in`: raw bytes, or base64 text (whitespace
// skipped; a header is encoded apart from its data). Fewer if the file ends.
std::vector<std::uint64_t> headerWords(std::istream& in,
  bool base64,
  const HeaderFormat& f,
  std::size_t count)
{
  const std::size_t size = static_cast<std::size_t>(f.wordSize);
  std::vector<unsigned char> bytes(count * size, 0);
  if (base64)
  {
    const std::size_t wanted = 4 * ((bytes.size() + 2) / 3); // 4 characters carry 3 bytes
    std::string chars;
    for (char c = 0; chars.size() < wanted && in.get(c);)
    {
      if (!std::isspace(static_cast<unsigned char>(c)))
      {
        chars.push_back(c);
      }
    }
    bytes.assign(wanted, 0);
    bytes.resize(
      vtkBase64Utilities::DecodeSafely(reinterpret_cast<const unsigned char*>(chars.data()),
        chars.size(),
        bytes.data(),
        bytes.size()));
  }
  else
  {
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
  }
  std::vector<std::uint64_t> words(std::min(count, bytes.size() / size), 0);
  for (std::size_t w = 0; w < words.size(); ++w)
  {
    for (std::size_t k = 0; k < size; ++k)
    {
      words[w] = (words[w] << 8) | bytes[w * size + (f.bigEndian ? k : size - 1 - k)];
    }
  }
  return words;
}

// Where an array's data starts: after its start tag (inline), or at its offset
// in the appended data.
struct DataStart
{
  std::streamoff position = 0;
  bool base64 = true;
};

void seekData(std::istream& in, const DataStart& start, bool inlineData)
{
  in.clear();
  in.seekg(start.position);
  for (char c = 0; inlineData && in.get(c) && c != '>';)
  {
  }
}

// deflate (zlib) expands a block at most 1032-fold, LZ4 at most 255-fold;
// LZMA can go further, so its blocks are not bounded this way.
constexpr std::uint64_t kMaxInflation = 1032;

// A compressed array's header: the number of blocks, the size of a block and
// of the last one (0: a full block), then each block's compressed size.
// vtkXMLDataParser allocates from these before it reads any data: a damaged
// count in a 5 KB file made it allocate 8 GB, a damaged block size 4 GB (and
// with 64-bit headers std::bad_alloc). Every size must fit in the file.
void checkCompressedHeader(std::istream& in,
  const DataStart& start,
  bool inlineData,
  const HeaderFormat& f,
  std::uint64_t fileSize,
  bool boundedInflation,
  const std::string& what)
{
  seekData(in, start, inlineData);
  const std::vector<std::uint64_t> head = headerWords(in, start.base64, f, 3);
  // A writer encodes the whole header as one unit, so all its words decode
  // before any padding. Fewer means a damaged header or a header_type that
  // does not match it; VTK's stream would read on into the data and take
  // whatever it finds there for sizes.
  if (head.size() < 3)
  {
    throw Error(what + " has a header shorter than its header_type says.");
  }
  const std::uint64_t blocks = head[0];
  if (blocks > fileSize / static_cast<std::uint64_t>(f.wordSize))
  {
    throw Error(what + " claims " + std::to_string(blocks) + " blocks, more than the file holds.");
  }
  seekData(in, start, inlineData);
  const std::vector<std::uint64_t> words =
    headerWords(in, start.base64, f, 3 + static_cast<std::size_t>(blocks));
  if (words.size() < 3 + blocks)
  {
    throw Error(
      what + " has a header shorter than its " + std::to_string(blocks) + " blocks need.");
  }
  for (std::size_t b = 0; b + 3 < words.size(); ++b)
  {
    const std::uint64_t compressed = words[b + 3];
    const std::uint64_t size = (b + 1 == blocks && head[2] != 0) ? head[2] : head[1];
    if (compressed > fileSize)
    {
      throw Error(what + " has a block of " + std::to_string(compressed) +
        " compressed bytes, more than the file holds.");
    }
    if (boundedInflation && size / kMaxInflation > compressed)
    {
      throw Error(what + " has a block of " + std::to_string(compressed) +
        " compressed bytes said to hold " + std::to_string(size) +
        ", more than its compressor can expand them to.");
    }
  }
}

void checkCompressedHeaders(vtkXMLDataParser* parser,
  const std::vector<vtkXMLDataElement*>& arrays,
  const std::string& path)
{
  vtkXMLDataElement* root = parser->GetRootElement();
  const std::string compressor = attribute(root, "compressor");
  if (compressor.empty())
  {
    return;
  }
  HeaderFormat f;
  f.wordSize = attribute(root, "header_type") == "UInt64" ? 8 : 4;
  f.bigEndian = attribute(root, "byte_order") == "BigEndian";
  const bool bounded = compressor != "vtkLZMADataCompressor";
  vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData");
  const bool appendedBase64 = appended != nullptr && attribute(appended, "encoding") == "base64";
  std::error_code ec;
  const auto fileSize = static_cast<std::uint64_t>(std::filesystem::file_size(path, ec));
  std::ifstream in(path, std::ios::binary);
  for (vtkXMLDataElement* a : arrays)
  {
    const std::string format = attribute(a, "format");
    const std::string what = path + " is damaged: its compressed data array " + arrayName(a);
    if (format == "binary")
    {
      checkCompressedHeader(in, { a->GetXMLByteIndex(), true }, true, f, fileSize, bounded, what);
    }
    else if (format == "appended")
    {
      long offset = 0;
      a->GetScalarAttribute("offset", offset);
      const DataStart start{ parser->GetAppendedDataPosition() + offset, appendedBase64 };
      checkCompressedHeader(in, start, false, f, fileSize, bounded, what);
    }
  }
}

// What vtkXMLPolyDataReader does not check and would crash or exhaust memory
// on, checked on the XML structure first.
void checkXmlStructure(const std::string& path)
{
  vtkNew<vtkXMLDataParser> parser;
  VtkErrorObserver observer;
  parser->AddObserver(vtkCommand::ErrorEvent, observer.callback);
  parser->SetFileName(path.c_str());
  if (parser->Parse() == 0 || observer.failed || parser->GetRootElement() == nullptr)
  {
    throw Error(path + " is not a VTK poly-data file that can be read.");
  }
  const std::vector<vtkXMLDataElement*> arrays = dataArrays(parser->GetRootElement());
  checkArrayTypes(arrays, path);
  checkComponentCounts(arrays, path);
  checkCompressedHeaders(parser, arrays, path);
}

} // namespace

void readPolyDataFile(const std::string& path, vtkPolyData* out)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throw Error("No such file: " + path + ".");
  }
  checkXmlStructure(path);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  readXmlDataFile(reader, path, "poly-data");
  checkPointIds(reader->GetOutput(), path);
  out->ShallowCopy(reader->GetOutput());
}

void writePolyDataFile(const std::string& path, vtkPolyData* data)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writeXmlDataFile(writer, data, path);
}

} // namespace tsynth
