/**
 * @class vtkTerrainLineWidthInitializationHelper
 * @brief Gives the representations of sketch lines and feature trees a thick default LineWidth.
 *
 * ParaView draws poly-lines 1 pixel wide: a drawn ridge or a feature tree over a 50 km terrain is
 * then a hairline. This initialization helper, named in the Hints of ParaView's
 * GeometryRepresentation (Plugin/TerrainLineWidths.xml), sets LineWidth on a new representation
 * whose input comes from one of the listed producers, when ParaView's pipeline controller
 * initializes it (vtkSMParaViewPipelineController::PostInitializeProxy: on Show and on Apply).
 *
 * Its XML element takes two attributes:
 * \code{.xml}
 * <InitializationHelper class="vtkTerrainLineWidthInitializationHelper"
 *   producers="TerrainSketchLines TerrainSynthesis:2" line_width="3"/>
 * \endcode
 * `producers` lists proxy XML names separated by spaces: "Name" covers every output port of
 * that proxy, "Name:N" its output port N only. `line_width` is the width in pixels.
 *
 * A width the user chose wins: one set on the representation before it was initialized (e.g.
 * `Show(source, view, LineWidth=5)` in pvpython), one changed afterwards, and one saved in the
 * user's or the site's settings (`.representations.GeometryRepresentation.LineWidth`, from
 * "Save current settings as default" in the Properties panel). A loaded state file keeps the
 * widths it holds: ParaView does not initialize the proxies it loads.
 */
#ifndef vtkTerrainLineWidthInitializationHelper_h
#define vtkTerrainLineWidthInitializationHelper_h

#include "TerrainSynthesisServerManagerModule.h" // For export macro
#include "vtkSMProxyInitializationHelper.h"

class TERRAINSYNTHESISSERVERMANAGER_EXPORT vtkTerrainLineWidthInitializationHelper
  : public vtkSMProxyInitializationHelper
{
public:
  static vtkTerrainLineWidthInitializationHelper* New();
  vtkTypeMacro(vtkTerrainLineWidthInitializationHelper, vtkSMProxyInitializationHelper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Sets the representation `proxy`'s LineWidth to the XML's line_width when its input is one
   * of the XML's producers, unless the width was set since `initializationTimeStamp` or is
   * saved in the settings.
   */
  void PostInitializeProxy(vtkSMProxy* proxy,
    vtkPVXMLElement* xml,
    vtkMTimeType initializationTimeStamp) override;

protected:
  vtkTerrainLineWidthInitializationHelper() = default;
  ~vtkTerrainLineWidthInitializationHelper() override = default;

private:
  vtkTerrainLineWidthInitializationHelper(const vtkTerrainLineWidthInitializationHelper&) = delete;
  void operator=(const vtkTerrainLineWidthInitializationHelper&) = delete;
};

#endif
