// Compares the integer tallies of two luxtrace result files bit for bit.
// Usage: h5_tally_compare A.h5 B.h5   (exit 0: identical, 1: different, 2: unreadable)
#include "luxtrace/io/result_reader.hpp"

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: h5_tally_compare A.h5 B.h5\n";
        return 2;
    }
    try {
        const luxtrace::ResultReader a(argv[1]), b(argv[2]);
        std::vector<std::string> names{"/global/count_odd", "/global/count_even", "/global/direct_odd",
                                       "/global/direct_even"};
        if (a.has("/global/sumsq") || b.has("/global/sumsq")) names.push_back("/global/sumsq");  // format 2
        for (const std::string& d : a.children("/detectors")) {
            names.push_back("/detectors/" + d + "/count");
            names.push_back("/detectors/" + d + "/sumsq");
            if (a.has("/detectors/" + d + "/replicate_count") || b.has("/detectors/" + d + "/replicate_count"))
                names.push_back("/detectors/" + d + "/replicate_count");  // sobol
        }
        // Light groups (issue 22): each group's own counts.
        for (const std::string& lg :
             a.has("/light_groups") ? a.children("/light_groups") : std::vector<std::string>{}) {
            const std::string g = "/light_groups/" + lg;
            for (const char* n : {"count_odd", "count_even", "direct_odd", "direct_even", "sumsq", "replicate_count"})
                if (a.has(g + "/" + n)) names.push_back(g + "/" + n);
            for (const std::string& d : a.children(g + "/detectors"))
                for (const char* n : {"count", "sumsq", "replicate_count"})
                    if (a.has(g + "/detectors/" + d + "/" + n)) names.push_back(g + "/detectors/" + d + "/" + n);
        }
        // Annual daylight (issue 24): every detector's coefficients per light group.
        for (const std::string& d :
             a.has("/annual/detectors") ? a.children("/annual/detectors") : std::vector<std::string>{})
            for (const char* n : {"count", "sumsq", "direct_count", "gathered", "gathered_sumsq"})
                if (a.has("/annual/detectors/" + d + "/coefficients/" + n))
                    names.push_back("/annual/detectors/" + d + "/coefficients/" + n);
        // ... and with direct = "shadow_rays", the direct exposure and every hour's values,
        // compared bit for bit as the tallies are.
        std::vector<std::string> reals;
        for (const std::string& d :
             a.has("/annual/detectors") ? a.children("/annual/detectors") : std::vector<std::string>{})
            if (a.has("/annual/detectors/" + d + "/shadow_direct_sky_lx_h"))
                for (const char* n :
                     {"shadow_direct_sky_lx_h", "shadow_direct_sky_sigma_lx_h", "shadow_direct_sun_lx_h",
                      "shadow_direct_sun_sigma_lx_h", "illuminance_lx", "illuminance_sigma_lx", "direct_sun_lx"})
                    reals.push_back("/annual/detectors/" + d + "/" + n);
        // ... and with indirect = "gather", the gathered exposure.
        for (const std::string& d :
             a.has("/annual/detectors") ? a.children("/annual/detectors") : std::vector<std::string>{})
            for (const char* n :
                 {"gathered_sky_lx_h", "gathered_sky_sigma_lx_h", "gathered_sun_lx_h", "gathered_sun_sigma_lx_h"})
                if (a.has("/annual/detectors/" + d + "/" + n)) reals.push_back("/annual/detectors/" + d + "/" + n);
        // The metrics and their replicates' errors, made block by block on every core
        // (issue 37): the same bits on any thread or rank count.
        for (const std::string& d :
             a.has("/annual/detectors") ? a.children("/annual/detectors") : std::vector<std::string>{})
            for (const char* m : {"da", "continuous_da", "udi_fell_short", "udi_useful", "udi_exceeded", "ase_hours"})
                for (const char* suffix : {"", "_sigma", "_bias"}) {
                    const std::string n = "/annual/detectors/" + d + "/" + m + suffix;
                    if (a.has(n)) reals.push_back(n);
                }
        int differ = 0;
        for (const std::string& n : reals) {
            const auto va = a.f64(n), vb = b.f64(n);
            std::size_t diff = va.size() == vb.size() ? 0 : 1;
            for (std::size_t i = 0; i < va.size() && i < vb.size(); ++i)
                diff += std::memcmp(&va[i], &vb[i], sizeof(double)) != 0;
            std::cout << n << ": " << va.size() << " values, " << diff << " differ\n";
            differ += diff != 0;
        }
        // ... and the grid figures (attributes of the grid's group), which rank 0 merges
        // from every rank's part when the ranks share the post-processing.
        std::vector<std::string> figures{"sda",
                                         "ase",
                                         "mean_da",
                                         "mean_continuous_da",
                                         "mean_udi_fell_short",
                                         "mean_udi_useful",
                                         "mean_udi_exceeded"};
        for (const char* level : {"minimum", "medium", "high"})
            for (const char* what : {"_target_hours", "_minimum_hours"})
                figures.push_back(std::string("en17037_") + level + what);
        for (const std::string& d :
             a.has("/annual/detectors") ? a.children("/annual/detectors") : std::vector<std::string>{}) {
            const std::string g = "/annual/detectors/" + d;
            std::size_t diff = 0, compared = 0;
            for (const std::string& f : figures)
                for (const char* suffix : {"", "_sigma", "_bias"})
                    if (a.has_attr(g, f + suffix)) {
                        const double x = a.attr_f64(g, f + suffix), y = b.attr_f64(g, f + suffix);
                        diff += std::memcmp(&x, &y, sizeof(double)) != 0;
                        ++compared;
                    }
            std::cout << g << ": " << compared << " grid figures, " << diff << " differ\n";
            differ += diff != 0;
        }
        if (a.attr_u64("/", "photons") != b.attr_u64("/", "photons")) {
            std::cout << "photons differ\n";
            ++differ;
        }
        for (const std::string& n : names) {
            const auto va = a.u64(n), vb = b.u64(n);
            std::size_t diff = va.size() == vb.size() ? 0 : 1;
            std::uint64_t total = 0;
            for (std::size_t i = 0; i < va.size() && i < vb.size(); ++i) {
                diff += va[i] != vb[i];
                total += va[i];
            }
            std::cout << n << ": " << va.size() << " entries, sum " << total << ", " << diff << " differ\n";
            differ += diff != 0;
        }
        return differ == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "h5_tally_compare: " << e.what() << '\n';
        return 2;
    }
}
