#include "luxtrace/material/ward_lobe.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace luxtrace {

namespace {

constexpr int kAlbedoNodes = 129;
// Proposals before a glossy photon is given up as absorbed. Each is accepted with
// probability at least a(cos_i) (1 + cos_i) / 2 >= 0.18 for alpha <= 1, so the cap is
// never reached in practice (0.82^200 ~ 1e-17).
constexpr int kMaxProposals = 200;

// The weight f cos_o / (rho_s q(wo)) of a reflection drawn by Ward's inversion (q: the
// density of W3 carried over to wo): 2 cos_o / (cos_i + cos_o) (W4), in (0, 2 / (1 + cos_i)].
double proposal_weight(double cos_i, double cos_o) { return 2.0 * cos_o / (cos_i + cos_o); }

// SplitMix64 over the bits of the three numbers a glossy event was given: more uniforms
// for the rejection's further proposals that depend on nothing but those numbers.
class ProposalStream {
public:
    ProposalStream(double a, double b, double c)
        : state_(std::bit_cast<std::uint64_t>(a) ^ std::rotl(std::bit_cast<std::uint64_t>(b), 21) ^
                 std::rotl(std::bit_cast<std::uint64_t>(c), 42)) {}
    double next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return static_cast<double>(z >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t state_;
};

}  // namespace

double ward_albedo_quadrature(double alpha, double cos_i) {
    // Local frame: n = z, wi = (sin_i, 0, cos_i), h at polar angle theta_h, azimuth phi.
    // cos_o = 2 (wi.h) cos_h - cos_i > 0 exactly where cos(phi) > k (below), and the
    // integrand is the weight W4 under Ward's density, so a = E[W4 [cos_o > 0]].
    constexpr int kU = 1024, kPhi = 64;
    const double ci = std::clamp(cos_i, 0.0, 1.0);
    const double si = std::sqrt(std::max(0.0, 1.0 - ci * ci));
    double sum = 0.0;
    for (int j = 0; j < kU; ++j) {
        const double u = (j + 0.5) / kU;
        const double tan2 = -alpha * alpha * std::log(u);
        const double ch = 1.0 / std::sqrt(1.0 + tan2), sh = std::sqrt(tan2) * ch;
        const double ss = si * sh;
        double phi0;  // the arc |phi| < phi0 reflects above the surface
        if (ss <= 0.0) {
            phi0 = 2.0 * ci * ch * ch > ci ? kPi : 0.0;
        } else {
            const double k = ci * (1.0 - 2.0 * ch * ch) / (2.0 * ch * ss);
            phi0 = k <= -1.0 ? kPi : (k >= 1.0 ? 0.0 : std::acos(k));
        }
        if (phi0 <= 0.0) continue;
        double arc = 0.0;
        for (int m = 0; m < kPhi; ++m) {
            const double phi = phi0 * (m + 0.5) / kPhi;
            const double cos_o = 2.0 * (ss * std::cos(phi) + ci * ch) * ch - ci;
            if (cos_o > 0.0) arc += proposal_weight(ci, cos_o);
        }
        sum += arc * phi0 / kPhi;  // the integral over 0 < phi < phi0
    }
    return sum / (kU * kPi);  // (2 / 2 pi) for both halves of the circle, 1 / kU per node
}

WardLobe::WardLobe(double alpha) : alpha_(alpha) {
    if (!(alpha > 0.0 && alpha <= kMaxRoughness)) throw std::invalid_argument("Ward roughness out of (0, 1]");
    table_.resize(kAlbedoNodes);
    for (int k = 0; k < kAlbedoNodes; ++k) {
        const double s = static_cast<double>(k) / (kAlbedoNodes - 1);
        table_[static_cast<std::size_t>(k)] = std::min(1.0, ward_albedo_quadrature(alpha, s * s));
    }
}

double WardLobe::brdf(const Vec3& wi, const Vec3& wo, const Vec3& n) const {
    if (glm::dot(wi, n) <= 0.0 || glm::dot(wo, n) <= 0.0) return 0.0;
    const Vec3 h = wi + wo;
    const double hh = glm::dot(h, h), hn = glm::dot(h, n);
    const double hn2 = hn * hn, a2 = alpha_ * alpha_;
    const double tan2 = (hh - hn2) / hn2;
    return hh / (kPi * a2 * hn2 * hn2) * std::exp(-tan2 / a2);
}

Vec3 WardLobe::sample_half(const Vec3& n, double u1, double u2) const {
    // tan^2(theta_h) = -alpha^2 ln(1 - u1) inverts the cumulative 1 - exp(-tan^2 / alpha^2).
    const double tan2 = -alpha_ * alpha_ * std::log(1.0 - u1);
    const double ch = 1.0 / std::sqrt(1.0 + tan2);
    return Frame::around(n).to_world(unit_at_azimuth(std::sqrt(tan2) * ch, ch, u2));
}

double WardLobe::albedo(double cos_i) const {
    const double x = std::sqrt(std::clamp(cos_i, 0.0, 1.0)) * (kAlbedoNodes - 1);
    const int k = std::min(static_cast<int>(x), kAlbedoNodes - 2);
    const double t = x - k;
    return (1.0 - t) * table_[static_cast<std::size_t>(k)] + t * table_[static_cast<std::size_t>(k + 1)];
}

std::optional<Vec3> WardLobe::reflect(const Vec3& dir, const Vec3& n, double u_survive, double u1, double u2) const {
    const Vec3 wi = -dir;
    const double cos_i = std::max(0.0, glm::dot(wi, n));
    const double a = albedo(cos_i);
    if (!(u_survive < a)) return std::nullopt;
    // Rejection: a proposal from W3 is kept with probability W4 / bound, so the kept
    // direction has density f cos / a; the survival above already carried a.
    const double bound = 2.0 / (1.0 + cos_i);
    double accept = u_survive / a;  // uniform on [0, 1) given survival
    ProposalStream more(u_survive, u1, u2);
    for (int p = 0; p < kMaxProposals; ++p) {
        if (p > 0) {
            u1 = more.next();
            u2 = more.next();
            accept = more.next();
        }
        const Vec3 h = sample_half(n, u1, u2);
        const double ih = glm::dot(wi, h);
        const Vec3 wo = 2.0 * ih * h - wi;
        const double cos_o = glm::dot(wo, n);
        if (ih <= 0.0 || cos_o <= 0.0) continue;
        if (accept * bound < proposal_weight(cos_i, cos_o)) return glm::normalize(wo);
    }
    return std::nullopt;
}

}  // namespace luxtrace
