// `luxtrace photometry FILE...`: what luxtrace makes of luminaire files, one block each.
#include "commands.hpp"

#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/photometry_distribution.hpp"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace luxtrace {
namespace {

const char* symmetry_name(const Photometry& p) {
    if (p.type != PhotometricType::C) return p.horizontal_deg.front() < 0.0 ? "-" : "lateral";
    switch (p.symmetry()) {
    case CPlaneSymmetry::Rotational: return "rotational";
    case CPlaneSymmetry::Quadrant: return "quadrant (C0-C90)";
    case CPlaneSymmetry::Bilateral: return "about C0-C180 (C0-C180 given)";
    case CPlaneSymmetry::Bilateral90: return "about C90-C270 (C90-C270 given)";
    case CPlaneSymmetry::Full: return "none (C0-C360)";
    }
    return "?";
}

}  // namespace

int cmd_photometry(const std::vector<std::string>& files, int lamp_set) {
    for (const std::string& f : files) {
        const Photometry p = load_photometry(f, lamp_set);
        const PhotometryDistribution dist(p);
        const char type = p.type == PhotometricType::C ? 'C' : p.type == PhotometricType::B ? 'B' : 'A';
        std::ostringstream out;
        out << std::setprecision(6);
        out << "file        " << f << '\n';
        out << "format      " << p.format << ", type " << type << ", symmetry " << symmetry_name(p) << '\n';
        if (!p.luminaire.empty()) out << "luminaire   " << p.luminaire.substr(0, p.luminaire.find('\n')) << '\n';
        out << "angles      " << p.horizontal_deg.size() << " horizontal " << p.horizontal_deg.front() << ".."
            << p.horizontal_deg.back() << ", " << p.vertical_deg.size() << " vertical " << p.vertical_deg.front()
            << ".." << p.vertical_deg.back() << '\n';
        out << "lamps       " << p.num_lamps << ", ";
        if (p.lamp_flux_lm > 0.0) out << p.lamp_flux_lm << " lm rated";
        else out << "absolute photometry";
        if (p.input_watts > 0.0) out << ", " << p.input_watts << " W";
        out << '\n';
        out << "flux        " << p.flux_lm() << " lm from the table";
        if (p.stated_flux_lm > 0.0)
            out << ", " << p.stated_flux_lm << " lm stated (lamps x LORL), ratio " << p.flux_lm() / p.stated_flux_lm;
        else if (p.lamp_flux_lm > 0.0) out << ", light output ratio " << p.flux_lm() / p.lamp_flux_lm;
        out << "; sampled " << dist.flux_lm() << " lm\n";
        // The brightest tabulated direction, in the file's own angles.
        double peak = -1.0, peak_h = 0.0, peak_v = 0.0;
        for (std::size_t j = 0; j < p.horizontal_deg.size(); ++j)
            for (std::size_t i = 0; i < p.vertical_deg.size(); ++i)
                if (p.candela_cd[j][i] > peak) {
                    peak = p.candela_cd[j][i];
                    peak_h = p.horizontal_deg[j];
                    peak_v = p.vertical_deg[i];
                }
        out << "peak        " << peak << " cd at " << (p.type == PhotometricType::C ? "C " : "H ") << peak_h
            << (p.type == PhotometricType::C ? ", gamma " : ", V ") << peak_v << " (of the file's planes)\n";
        out << "opening     " << shape_name(p.opening.shape);
        if (p.opening.shape != LuminousOpening::Shape::point)
            out << ", length " << p.opening.length_m << " m, width " << p.opening.width_m << " m, height "
                << p.opening.height_m << " m";
        out << '\n';
        if (!p.tilt.empty()) {
            out << "tilt        geometry " << p.tilt.lamp_geometry << ", " << p.tilt.angle_deg.size() << " angles "
                << p.tilt.angle_deg.front() << ".." << p.tilt.angle_deg.back() << ", multipliers";
            for (double m : p.tilt.multiplier) out << ' ' << m;
            out << '\n';
        }
        for (const std::string& n : p.notes) out << "note        " << n << '\n';
        std::cout << out.str() << '\n';
    }
    return 0;
}

}  // namespace luxtrace
