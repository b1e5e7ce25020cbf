#include "vtkTerrainLineWidthInitializationHelper.h"

#include "vtkObjectFactory.h"
#include "vtkPVXMLElement.h"
#include "vtkSMInputProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMSettings.h"

#include <sstream>
#include <string>

namespace
{

// The user's or the site's saved default width of poly-data representations; when there is
// one, it is what the user asked for, and ParaView has already applied it.
constexpr const char* kLineWidthSetting = ".representations.GeometryRepresentation.LineWidth";

// The width when the XML gives none: thick enough to read a line over a 50 km terrain in the
// 2D view, thin enough not to hide the relief beside it.
constexpr double kDefaultLineWidth = 3.0;

// Port numbers longer than this are refused: nine digits always fit std::stoul's result.
constexpr std::string::size_type kMaxPortDigits = 9;

// The XML's line_width, or the default when it gives none; 0 when it gives a width that is
// not a positive number.
double lineWidthOf(vtkPVXMLElement* xml)
{
  if (xml->GetAttribute("line_width") == nullptr)
  {
    return kDefaultLineWidth;
  }
  double width = 0.0;
  return xml->GetScalarAttribute("line_width", &width) && width > 0.0 ? width : 0.0;
}

// Whether one entry of a producers list ("Name" or "Name:N") covers output port `port` of the
// proxy with XML name `producer`. An entry whose port is not a number covers nothing.
bool covers(const std::string& entry, const std::string& producer, unsigned int port)
{
  const std::string::size_type colon = entry.find(':');
  if (entry.compare(0, colon, producer) != 0)
  {
    return false;
  }
  if (colon == std::string::npos)
  {
    return true; // every output port
  }
  const std::string digits = entry.substr(colon + 1);
  if (digits.empty() || digits.size() > kMaxPortDigits ||
    digits.find_first_not_of("0123456789") != std::string::npos)
  {
    return false;
  }
  return std::stoul(digits) == port;
}

} // namespace

vtkStandardNewMacro(vtkTerrainLineWidthInitializationHelper);

void vtkTerrainLineWidthInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  // No state: the producers and the width come with each call, from the proxy's XML hints.
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LineWidthSetting: " << kLineWidthSetting << "\n";
  os << indent << "DefaultLineWidth: " << kDefaultLineWidth << "\n";
}

void vtkTerrainLineWidthInitializationHelper::PostInitializeProxy(vtkSMProxy* proxy,
  vtkPVXMLElement* xml,
  vtkMTimeType initializationTimeStamp)
{
  vtkSMProperty* width = proxy->GetProperty("LineWidth");
  auto* input = vtkSMInputProperty::SafeDownCast(proxy->GetProperty("Input"));
  if (width == nullptr || input == nullptr || input->GetNumberOfProxies() == 0 ||
    width->GetMTime() > initializationTimeStamp ||
    vtkSMSettings::GetInstance()->HasSetting(kLineWidthSetting))
  {
    return; // not a representation of lines, or the user chose its width
  }
  vtkSMProxy* producer = input->GetProxy(0);
  if (producer == nullptr || producer->GetXMLName() == nullptr)
  {
    return;
  }
  const unsigned int port = input->GetOutputPortForConnection(0);
  std::istringstream producers(xml->GetAttributeOrDefault("producers", ""));
  for (std::string entry; producers >> entry;)
  {
    if (covers(entry, producer->GetXMLName(), port))
    {
      const double lineWidth = lineWidthOf(xml);
      if (lineWidth <= 0.0)
      {
        vtkWarningMacro("The InitializationHelper's line_width \""
          << xml->GetAttribute("line_width")
          << "\" is not a positive number of pixels; give one, e.g. line_width=\"3\".");
        return;
      }
      vtkSMPropertyHelper(width).Set(lineWidth);
      proxy->UpdateVTKObjects();
      return;
    }
  }
}
