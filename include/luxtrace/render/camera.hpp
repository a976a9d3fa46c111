#pragma once
// The eye of `luxtrace render`: a pinhole camera given by position, target, up and a
// horizontal field of view, plus the parsing of the command-line forms of a view.
#include "luxtrace/core/math.hpp"

#include <string>
#include <utility>

namespace luxtrace {

struct Camera;

class PinholeCamera {
public:
    // Throws InputError (starting with `what`, e.g. "--camera") if target == position,
    // up is parallel to the view, the field of view is outside (0, 180) degrees or the
    // size is not 1..16384 pixels each way.
    PinholeCamera(const Vec3& position, const Vec3& target, const Vec3& up, double fov_deg, int width, int height,
                  const std::string& what = "camera");
    explicit PinholeCamera(const Camera& c);

    int width() const { return width_; }
    int height() const { return height_; }
    const Vec3& position() const { return position_; }

    // Unit direction through the image point (x, y) in pixels: (0, 0) is the top-left
    // corner of the image, x grows to the right, y downward; pixel (i, j) covers
    // [i, i+1) x [j, j+1). Square pixels, so the vertical field follows from the size.
    Vec3 direction(double x, double y) const;

private:
    Vec3 position_, forward_, right_, up_;
    double tan_half_ = 1.0;  // tan(fov/2): half the image width at unit distance
    int width_ = 1, height_ = 1;
};

// "px,py,pz,tx,ty,tz[,ux,uy,uz]" -> Camera (up defaults to +z); throws InputError naming
// --camera and what is wrong. fov and size are left at the Camera defaults.
Camera parse_camera_option(const std::string& text);

// "WxH" -> {W, H}, each 1..16384; throws InputError naming --size.
std::pair<int, int> parse_size_option(const std::string& text);

}  // namespace luxtrace
