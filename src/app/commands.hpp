#pragma once
// Subcommands beyond run/check/info, each in its own source file under src/app/.
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

struct RenderArgs {
    std::string result;       // result file (.h5)
    std::string camera;       // "px,py,pz,tx,ty,tz[,ux,uy,uz]" or empty
    std::string camera_name;  // a [[camera]] of the scene file
    std::optional<double> fov_deg;
    std::string size;                // "WxH"
    std::string output;              // -o: view.png (an .exr/.pfm beside it holds luminance)
    std::string tonemap = "auto";    // auto | exposure | falsecolour
    std::optional<double> exposure;  // exposure mapping: cd/m^2 shown as white
    double gamma = 2.2;
    std::optional<double> falsecolour_max;  // cd/m^2 at the top of the scale
    int samples = 4;                        // rays per pixel (anti-aliasing)
    int threads = 0;
    std::string light_scene;  // --scene: render a [[light_scene]] of the run
};

// `luxtrace render`: exit code 0, or throws InputError for bad input.
int cmd_render(const RenderArgs& args);
// `luxtrace photometry FILE...`: how each luminaire file reads (format, flux, opening).
int cmd_photometry(const std::vector<std::string>& files, int lamp_set);
// `luxtrace export-xdmf RESULT.h5 [-o FILE.xdmf]`.
int cmd_export_xdmf(const std::string& result, const std::string& output);

}  // namespace luxtrace
