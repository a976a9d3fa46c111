#include "luxtrace/light/sky_patches.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace luxtrace {

namespace {

// Tregenza's patches per 12-degree row, horizon up (Tregenza 1987; Radiance's tnaz).
constexpr std::array<int, 7> kTregenzaRow{30, 30, 24, 24, 18, 12, 6};
constexpr int kMaxNodes = 64;
constexpr double kDegree = kPi / 180.0;

struct GaussRule {
    std::vector<double> x, w;  // nodes and weights on [-1, 1]
};

// P_n(x) and P_n'(x) by the three-term recurrence (Abramowitz & Stegun 22.7.10, 22.8.5).
std::pair<double, double> legendre(int n, double x) {
    double p0 = 1.0, p1 = x;
    for (int j = 2; j <= n; ++j) {
        const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
        p0 = p1;
        p1 = p2;
    }
    return {p1, n * (x * p1 - p0) / (x * x - 1.0)};
}

// The n-point Gauss-Legendre rule: roots of P_n by Newton's method from Tricomi's initial
// guess, weights 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz & Stegun 25.4.29).
GaussRule gauss_legendre(int n) {
    GaussRule g{std::vector<double>(static_cast<std::size_t>(n)), std::vector<double>(static_cast<std::size_t>(n))};
    for (int k = 0; k < (n + 1) / 2; ++k) {
        double x = std::cos(kPi * (k + 0.75) / (n + 0.5));
        for (int iter = 0; iter < 100; ++iter) {
            const auto [p, dp] = legendre(n, x);
            const double dx = p / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        if (n % 2 == 1 && k == n / 2) x = 0.0;  // the middle root exactly
        const double dp = legendre(n, x).second;
        const auto lo = static_cast<std::size_t>(k), hi = static_cast<std::size_t>(n - 1 - k);
        g.x[lo] = -x;
        g.x[hi] = x;
        g.w[lo] = g.w[hi] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return g;
}

// The unit direction at sin(altitude) s and azimuth phi (radians, clockwise from north).
Vec3 direction_at(double s, double phi) {
    const double c = std::sqrt(std::max(0.0, 1.0 - s * s));
    return {c * std::sin(phi), c * std::cos(phi), s};
}

}  // namespace

SkyPatches::SkyPatches(int mf) : alpha_deg_(0.0) {
    if (mf < 1 || mf > kMaxMf)
        throw std::invalid_argument("sky patch subdivision MF " + std::to_string(mf) + " is not 1 to " +
                                    std::to_string(kMaxMf));
    const int bands = 7 * mf;  // rows below the zenith cap
    alpha_deg_ = 90.0 / (bands + 0.5);
    const double alpha_rad = (kPi / 2.0) / (bands + 0.5);
    for (int r = 0; r <= bands; ++r) {
        row_sin_.push_back(std::sin(r * alpha_rad));
        row_first_.push_back(patches_.size());
        const int n = r < bands ? mf * kTregenzaRow[static_cast<std::size_t>(r / mf)] : 1;
        const double w = 360.0 / n;
        for (int c = 0; c < n; ++c) {
            if (r == bands) patches_.push_back({r * alpha_deg_, 90.0, 0.0, 360.0, r, 0});
            else patches_.push_back({r * alpha_deg_, (r + 1) * alpha_deg_, (c - 0.5) * w, (c + 0.5) * w, r, c});
        }
    }
    row_sin_.push_back(1.0);
    row_first_.push_back(patches_.size());
}

std::size_t SkyPatches::row_count(int row) const {
    const auto r = static_cast<std::size_t>(row);
    return row_first_[r + 1] - row_first_[r];
}

SkyPatches::Box SkyPatches::box(std::size_t i) const {
    const Patch& p = patches_[i];
    const auto r = static_cast<std::size_t>(p.row);
    return {row_sin_[r], row_sin_[r + 1], p.az_lo_deg * kDegree, p.az_hi_deg * kDegree};
}

double SkyPatches::solid_angle_sr(std::size_t i) const {
    const Box b = box(i);
    return (b.s_hi - b.s_lo) * (b.phi_hi - b.phi_lo);
}

double SkyPatches::projected_solid_angle_sr(std::size_t i) const {
    const Box b = box(i);
    return 0.5 * (b.s_hi - b.s_lo) * (b.s_hi + b.s_lo) * (b.phi_hi - b.phi_lo);
}

Vec3 SkyPatches::center(std::size_t i) const {
    const Patch& p = patches_[i];
    if (i + 1 == count()) return {0.0, 0.0, 1.0};
    const double alt = 0.5 * (p.alt_lo_deg + p.alt_hi_deg) * kDegree;
    return direction_at(std::sin(alt), 0.5 * (p.az_lo_deg + p.az_hi_deg) * kDegree);
}

std::size_t SkyPatches::index_of(const Vec3& dir) const {
    const double len = glm::length(dir);
    const double s = dir.z / len;
    if (!(s >= 0.0)) return count();
    const int top = rows() - 1;
    // The row from the altitude, then settled against the stored bounds in sin(altitude).
    int r = std::clamp(static_cast<int>(std::asin(std::min(s, 1.0)) / kDegree / alpha_deg_), 0, top);
    while (r > 0 && s < row_sin_[static_cast<std::size_t>(r)]) --r;
    while (r < top && s >= row_sin_[static_cast<std::size_t>(r) + 1]) ++r;
    const std::size_t first = row_first_[static_cast<std::size_t>(r)];
    if (r == top) return first;
    const auto n = static_cast<long>(row_count(r));
    double az = std::atan2(dir.x, dir.y) / kDegree;
    if (az < 0.0) az += 360.0;
    const double w = 360.0 / static_cast<double>(n);
    long c = static_cast<long>(std::floor((az + 0.5 * w) / w));
    if (c >= n) c -= n;  // past 360 - w / 2: column 0, which straddles north
    return first + static_cast<std::size_t>(c);
}

Vec3 SkyPatches::sample(std::size_t i, double u1, double u2) const {
    const Box b = box(i);
    return direction_at(b.s_lo + u1 * (b.s_hi - b.s_lo), b.phi_lo + u2 * (b.phi_hi - b.phi_lo));
}

void SkyPatches::cut_at(std::vector<Box>& pieces, const Vec3& cusp) {
    const double s_c = cusp.z / glm::length(cusp);
    const double phi = std::atan2(cusp.x, cusp.y);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        const Box b = pieces[k];
        double phi_c = phi;
        while (phi_c < b.phi_lo) phi_c += 2.0 * kPi;
        if (phi_c > b.phi_hi || s_c < b.s_lo || s_c > b.s_hi) continue;
        // Up to four boxes with the cusp on their corners.
        pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(k));
        for (const auto& [s0, s1] : {std::pair{b.s_lo, s_c}, std::pair{s_c, b.s_hi}})
            for (const auto& [p0, p1] : {std::pair{b.phi_lo, phi_c}, std::pair{phi_c, b.phi_hi}})
                if (s1 > s0 && p1 > p0) pieces.push_back({s0, s1, p0, p1});
        return;
    }
}

std::vector<double> SkyPatches::cosine_weighted_means(const std::function<double(const Vec3&)>& L, int nodes,
                                                      const std::optional<Vec3>& cusp) const {
    return means(L, nodes, cusp, true);
}

std::vector<double> SkyPatches::solid_angle_means(const std::function<double(const Vec3&)>& L, int nodes,
                                                  const std::optional<Vec3>& cusp) const {
    return means(L, nodes, cusp, false);
}

template <class Node>
void SkyPatches::box_nodes(const std::vector<double>& x, const std::vector<double>& w, const Box& b, bool polar,
                           bool cosine_weighted, Node node) {
    // Integrals of L w and of w over a box, w = sin(altitude) or 1, by the product rule in
    // (sin altitude, azimuth); in the zenith cap in (zenith angle, azimuth) instead, since
    // directions are not smooth in sin altitude at the zenith.
    const double v_lo = polar ? std::acos(std::min(1.0, b.s_hi)) : b.s_lo;
    const double v_hi = polar ? std::acos(b.s_lo) : b.s_hi;
    const double v_mid = 0.5 * (v_hi + v_lo), v_half = 0.5 * (v_hi - v_lo);
    const double phi_mid = 0.5 * (b.phi_hi + b.phi_lo), phi_half = 0.5 * (b.phi_hi - b.phi_lo);
    for (std::size_t a = 0; a < x.size(); ++a) {
        const double v = v_mid + v_half * x[a];
        const double s = polar ? std::cos(v) : v;
        const double ws = w[a] * v_half * phi_half * (polar ? std::sin(v) : 1.0) * (cosine_weighted ? s : 1.0);
        for (std::size_t k = 0; k < x.size(); ++k) node(direction_at(s, phi_mid + phi_half * x[k]), ws * w[k]);
    }
}

void SkyPatches::pieces_of(std::size_t i, const std::optional<Vec3>& cusp, std::vector<Box>& pieces) const {
    const Box b = box(i);
    const bool polar = i + 1 == count();
    // The cap in as many azimuth sectors as the row below has patches: a sky that varies
    // fast near its rim (a sun just below it) is then resolved as in that row.
    pieces.clear();
    const int sectors = polar ? static_cast<int>(row_count(rows() - 2)) : 1;
    for (int k = 0; k < sectors; ++k) {
        const double w = (b.phi_hi - b.phi_lo) / sectors;
        pieces.push_back({b.s_lo, b.s_hi, b.phi_lo + k * w, k + 1 == sectors ? b.phi_hi : b.phi_lo + (k + 1) * w});
    }
    if (cusp && i == index_of(*cusp)) cut_at(pieces, *cusp);
}

std::vector<double> SkyPatches::means(const std::function<double(const Vec3&)>& L, int nodes,
                                      const std::optional<Vec3>& cusp, bool cosine_weighted) const {
    return means(quadrature(nodes, cosine_weighted), L, cusp);
}

SkyPatches::Quadrature SkyPatches::quadrature(int nodes, bool cosine_weighted) const {
    if (nodes < 1 || nodes > kMaxNodes)
        throw std::invalid_argument("quadrature nodes " + std::to_string(nodes) + " is not 1 to " +
                                    std::to_string(kMaxNodes));
    const GaussRule g = gauss_legendre(nodes);
    Quadrature q;
    q.nodes = nodes;
    q.cosine_weighted = cosine_weighted;
    std::vector<Box> pieces;
    for (std::size_t i = 0; i < count(); ++i) {
        q.first.push_back(q.direction.size());
        pieces_of(i, std::nullopt, pieces);
        double total = 0.0;
        for (const Box& piece : pieces)
            box_nodes(g.x, g.w, piece, i + 1 == count(), cosine_weighted, [&](const Vec3& d, double w) {
                q.direction.push_back(d);
                q.weight.push_back(w);
                total += w;
            });
        q.total.push_back(total);
    }
    q.first.push_back(q.direction.size());
    return q;
}

std::vector<double> SkyPatches::means(const Quadrature& q, const std::function<double(const Vec3&)>& L,
                                      const std::optional<Vec3>& cusp) const {
    const std::size_t cusp_patch = cusp ? index_of(*cusp) : count();
    std::vector<double> out(count());
    for (std::size_t i = 0; i < count(); ++i) {
        double num = 0.0, den = 0.0;
        if (i != cusp_patch) {
            for (std::size_t n = q.first[i]; n < q.first[i + 1]; ++n) num += q.weight[n] * L(q.direction[n]);
            den = q.total[i];
        } else {
            // The sun's patch, cut at the sun: its own nodes.
            const GaussRule g = gauss_legendre(q.nodes);
            std::vector<Box> pieces;
            pieces_of(i, cusp, pieces);
            for (const Box& piece : pieces)
                box_nodes(g.x, g.w, piece, i + 1 == count(), q.cosine_weighted, [&](const Vec3& d, double w) {
                    num += w * L(d);
                    den += w;
                });
        }
        out[i] = num / den;
    }
    return out;
}

}  // namespace luxtrace
