// Reading VTK XML files (.vtp, .vti) so that a damaged file gives one sentence:
// VTK's messages are kept off the terminal while it reads, and every data array
// is checked to hold as many values as its piece needs before VTK's own reader
// copies them (ParaView 5.11's reader crashes on a cell or point array shorter
// than its piece).
#pragma once

#include <string>

class vtkDataObject;
class vtkXMLReader;
class vtkXMLWriter;

namespace tsynth
{

// Runs `reader` (file name set) to its output. Throws tsynth::Error naming
// `path` ("... is not a VTK <what> file that can be read", or which array is
// too short) on any failure.
void readXmlDataFile(vtkXMLReader* reader, const std::string& path, const std::string& what);

// Writes `data` with `writer` (inline binary, zlib: ParaView 5.11 with Debian 12's expat
// cannot read appended data) to a temporary beside `path` and publishes it (OutputFile).
// Throws tsynth::Error naming `path`, with VTK's reason kept off the terminal, if any write
// fails (a full disk included).
void writeXmlDataFile(vtkXMLWriter* writer, vtkDataObject* data, const std::string& path);

} // namespace tsynth
