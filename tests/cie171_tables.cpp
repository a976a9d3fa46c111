// Prints the exact sky components of the CIE 171:2006 daylight test cases next to the
// report's published values, as the Markdown tables of docs/VALIDATION.md ("CIE 171:2006
// daylight test cases"): build/tests/cie171_tables > tables.md. A published value that
// differs from the exact one by more than its rounding (0.005) plus 0.5 % is marked with
// a dagger; docs/VALIDATION.md says which of those are errata.
#include "cie171_cases.hpp"

#include <cmath>
#include <cstdio>

int main() {
    using namespace luxtrace::cie171;
    for (const Case& c : report_cases()) {
        std::printf("\n#### %s: %s (tables %s)\n\n| point |", c.id.c_str(), c.title.c_str(), c.table.c_str());
        for (const int t : kSkyTypes) std::printf(" type %d published | type %d exact |", t, t);
        std::printf("\n|---|");
        for (std::size_t i = 0; i < std::size(kSkyTypes); ++i) std::printf("---:|---:|");
        std::printf("\n");
        for (std::size_t p = 0; p < c.points.size(); ++p) {
            std::printf("| %s |", c.points[p].label.c_str());
            for (std::size_t t = 0; t < std::size(kSkyTypes); ++t) {
                const double pub = c.published[t][p], exact = exact_sc_percent(c, c.points[p], kSkyTypes[t]);
                const bool differs = std::abs(pub - exact) > 0.005 + 0.005 * exact;
                std::printf(" %.2f%s | %.3f |", pub, differs ? " †" : "", exact);
            }
            std::printf("\n");
        }
    }
    std::printf("\n### Cell averages of the luxtrace runs\n\n| scene | CIE type | detector | exact SC per cell, %% "
                "(cell 0 first) |\n|---|---:|---|---|\n");
    for (const RunCase& rc : run_cases())
        for (const Strip& s : rc.strips) {
            std::printf("| %s (%s) | %d | %s |", rc.scene.c_str(), rc.section.c_str(), rc.cie_type, s.name.c_str());
            for (int k = 0; k < s.cells; ++k)
                std::printf(" %.3f", 100.0 * exact_cell_lx(rc, s, k) / kDiffuseHorizontalLx);
            std::printf(" |\n");
        }
}
