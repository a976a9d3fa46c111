#include "luxtrace/render/camera.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/scene.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace luxtrace {

namespace {

constexpr int kMaxPixels = 16384;

// Strict number parsing: the whole field must be a finite number.
bool parse_number(const std::string& field, double& out) {
    if (field.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(field.c_str(), &end);
    return errno == 0 && end == field.c_str() + field.size() && std::isfinite(out);
}

std::vector<std::string> split(const std::string& text, char sep) {
    std::vector<std::string> out(1);
    for (char c : text) {
        if (c == sep) out.emplace_back();
        else if (c != ' ') out.back() += c;
    }
    return out;
}

}  // namespace

PinholeCamera::PinholeCamera(const Vec3& position, const Vec3& target, const Vec3& up, double fov_deg, int width,
                             int height, const std::string& what)
    : position_(position), width_(width), height_(height) {
    const Vec3 view = target - position;
    if (!(glm::length(view) > 1e-9)) throw InputError(what + ": target must differ from position");
    forward_ = glm::normalize(view);
    if (!(glm::length(up) > 1e-12)) throw InputError(what + ": up must be a non-zero vector");
    const Vec3 right = glm::cross(forward_, glm::normalize(up));
    if (!(glm::length(right) > 1e-9)) throw InputError(what + ": up must not be parallel to the viewing direction");
    right_ = glm::normalize(right);
    up_ = glm::cross(right_, forward_);
    if (!(fov_deg > 0.0 && fov_deg < 180.0))
        throw InputError(what + ": field of view " + std::to_string(fov_deg) + " deg must lie in (0, 180)");
    if (!(width >= 1 && height >= 1 && width <= kMaxPixels && height <= kMaxPixels))
        throw InputError(what + ": image size must be 1..16384 pixels each way");
    tan_half_ = std::tan(0.5 * fov_deg * kPi / 180.0);
}

PinholeCamera::PinholeCamera(const Camera& c)
    : PinholeCamera(c.position, c.target, c.up, c.fov_deg, c.width, c.height,
                    c.name.empty() ? std::string("camera") : "camera '" + c.name + "'") {}

Vec3 PinholeCamera::direction(double x, double y) const {
    const double sx = (2.0 * x / width_ - 1.0) * tan_half_;
    const double sy = (1.0 - 2.0 * y / height_) * tan_half_ * height_ / width_;
    return glm::normalize(forward_ + sx * right_ + sy * up_);
}

Camera parse_camera_option(const std::string& text) {
    const std::vector<std::string> fields = split(text, ',');
    if (fields.size() != 6 && fields.size() != 9)
        throw InputError("--camera: '" + text +
                         "' must be 6 or 9 comma-separated numbers "
                         "(position, target[, up]), got " +
                         std::to_string(fields.size()));
    double v[9] = {0, 0, 0, 0, 0, 0, 0, 0, 1};
    for (std::size_t i = 0; i < fields.size(); ++i)
        if (!parse_number(fields[i], v[i]))
            throw InputError("--camera: field " + std::to_string(i + 1) + " '" + fields[i] + "' is not a number");
    Camera c;
    c.position = Vec3(v[0], v[1], v[2]);
    c.target = Vec3(v[3], v[4], v[5]);
    c.up = Vec3(v[6], v[7], v[8]);
    // Same checks as the renderer makes, so the message names the option.
    PinholeCamera(c.position, c.target, c.up, c.fov_deg, c.width, c.height, "--camera");
    return c;
}

std::pair<int, int> parse_size_option(const std::string& text) {
    const auto x = text.find_first_of("xX");
    double w = 0.0, h = 0.0;
    if (x == std::string::npos || !parse_number(text.substr(0, x), w) || !parse_number(text.substr(x + 1), h) ||
        w != std::floor(w) || h != std::floor(h))
        throw InputError("--size: '" + text + "' must read WxH in whole pixels, e.g. 800x600");
    if (!(w >= 1 && h >= 1 && w <= kMaxPixels && h <= kMaxPixels))
        throw InputError("--size: '" + text + "': width and height must be 1..16384 pixels");
    return {static_cast<int>(w), static_cast<int>(h)};
}

}  // namespace luxtrace
