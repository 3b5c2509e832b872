#include "figure.hpp"

#include "offscreen_display.hpp"

#include <core/files.hpp>

#include <filesystem>
#include <functional>
#include <system_error>

#ifdef SPREADMAP_RENDER_GL2PS
#include <vtkGL2PSExporter.h>
#endif
#include <vtkPNGWriter.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace spreadmap::render::detail {

namespace {
std::mutex rendering_mutex;
const char* dejavu_sans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
const char* dejavu_sans_bold = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

// Through the host's one atomic writer; its own failures become RenderErrors, like every error here.
void write_file(const fs::path& target, const std::function<void(const fs::path& tmp)>& write) {
  try {
    sm::write_atomic_with(target, write);
  } catch (const RenderError&) {
    throw;
  } catch (const std::exception& e) {
    throw RenderError(e.what());
  }
}

bool empty_file(const fs::path& file) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  return ec || size == 0;
}
}  // namespace

std::unique_lock<std::mutex> lock_rendering() { return std::unique_lock(rendering_mutex); }

bool unicode_text() {
  static const bool found = fs::exists(dejavu_sans) && fs::exists(dejavu_sans_bold);
  return found;
}

void style_text(vtkTextProperty* p, double size_px, const Rgb& colour, bool bold) {
  if (unicode_text()) {
    p->SetFontFamily(VTK_FONT_FILE);
    p->SetFontFile(bold ? dejavu_sans_bold : dejavu_sans);
  } else {
    p->SetFontFamilyToArial();
    p->SetBold(bold);
  }
  p->SetFontSize(static_cast<int>(size_px + 0.5));
  p->SetColor(colour[0], colour[1], colour[2]);
  p->SetShadow(false);
  p->SetItalic(false);
}

DisplayUnit display_unit(const std::string& si) {
  const bool u = unicode_text();
  if (si == "m^2/s" || si == "m2/s") return {1e6, u ? "mm²/s" : "mm^2/s"};
  if (si == "m") return {1e6, u ? "µm" : "um"};
  if (si == "m/s") return {1e3, "mm/s"};
  if (si == "rad/s") return {1.0, "rad/s"};
  if (si == "m^3/s") return {1e9, u ? "mm³/s" : "mm^3/s"};
  return {1.0, si};
}

std::string omega_symbol() { return unicode_text() ? "ω" : "omega"; }

std::string axis_label(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == "-" ? name : name + " [" + unit + "]";
}

std::string pretty_name(const std::string& name) { return name; }

Figure::Figure(const Options& opt) : opt_(opt) {
  if (opt_.width < 16 || opt_.height < 16 || opt_.width > 3840 || opt_.height > 2400)
    throw RenderError("render: figure size " + std::to_string(opt_.width) + "x" + std::to_string(opt_.height) +
                      " is outside 16x16 .. 3840x2400 pixels; choose a size inside it");
  ensure_display();
  window_->SetOffScreenRendering(1);
  window_->SetSize(opt_.width, opt_.height);
  window_->SetMultiSamples(0);  // software GL: FXAA below is cheaper and portable
  window_->AddRenderer(renderer_);
  renderer_->SetBackground(1, 1, 1);
}

void Figure::add_title() {
  if (opt_.title.empty()) return;
  vtkNew<vtkTextActor> t;
  t->SetInput(opt_.title.c_str());
  style_text(t->GetTextProperty(), 30 * scale(), {0, 0, 0}, true);
  t->GetTextProperty()->SetJustificationToCentered();
  t->GetTextProperty()->SetVerticalJustificationToTop();
  t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  t->SetPosition(opt_.width / 2.0, opt_.height - 12 * scale());
  renderer_->AddActor2D(t);
}

void Figure::write(const fs::path& png) {
  window_->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window_);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  int* dims = grab->GetOutput()->GetDimensions();
  if (dims[0] != opt_.width || dims[1] != opt_.height)
    throw RenderError("render: the X server gave a " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) +
                      " image instead of " + std::to_string(opt_.width) + "x" + std::to_string(opt_.height) + " for " +
                      png.string() + "; use a smaller figure or a larger screen");
  write_file(png, [&](const fs::path& tmp) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    if (writer->GetErrorCode() != 0 || empty_file(tmp))
      throw RenderError("render: cannot write " + png.string() + "; check that the folder is writable and has space");
  });

  if (!opt_.vector_format.empty()) {
#ifndef SPREADMAP_RENDER_GL2PS
    throw RenderError("render: this build's VTK has no gl2ps exporter, so vector_format '" + opt_.vector_format +
                      "' cannot be written; leave vector_format empty");
#else
    vtkNew<vtkGL2PSExporter> exporter;
    exporter->SetRenderWindow(window_);
    const std::string f = opt_.vector_format;
    if (f == "pdf") exporter->SetFileFormatToPDF();
    else if (f == "svg") exporter->SetFileFormatToSVG();
    else if (f == "eps") exporter->SetFileFormatToEPS();
    else if (f == "ps") exporter->SetFileFormatToPS();
    else throw RenderError("render: vector format '" + f + "' is not one of pdf, svg, eps, ps");
    exporter->CompressOff();
    exporter->SetSortToBSP();
    exporter->DrawBackgroundOn();
    exporter->Write3DPropsAsRasterImageOff();
    fs::path copy = png;
    copy.replace_extension(f);
    write_file(copy, [&](const fs::path& tmp) {
      fs::path prefix = tmp;  // the exporter appends "." + f to its prefix
      prefix.replace_extension();
      exporter->SetFilePrefix(prefix.c_str());
      exporter->Write();
      if (empty_file(tmp))
        throw RenderError("render: gl2ps wrote nothing for " + copy.string() + "; leave vector_format empty");
    });
#endif
  }
}

}  // namespace spreadmap::render::detail

namespace spreadmap::render {
bool vector_output_available() {
#ifdef SPREADMAP_RENDER_GL2PS
  return true;
#else
  return false;
#endif
}
}  // namespace spreadmap::render
