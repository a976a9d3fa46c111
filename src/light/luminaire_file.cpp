#include "luxtrace/light/luminaire_file.hpp"

#include "luxtrace/light/eulumdat.hpp"
#include "luxtrace/light/ies.hpp"
#include "photometry_text.hpp"

namespace luxtrace {

PhotometryFormat detect_photometry_format(const std::filesystem::path& file) {
    const std::vector<std::string> lines = detail::read_lines(file, "photometric file");
    for (const std::string& l : lines) {
        const std::string_view t = detail::trim(l);
        if (t.size() >= 4 && detail::iequals(t.substr(0, 4), "TILT") && detail::trim(t.substr(4)).starts_with('='))
            return PhotometryFormat::ies;
    }
    bool numbers = lines.size() > 7;
    for (std::size_t k = 1; numbers && k < 7; ++k) numbers = detail::parse_number(lines[k], true).has_value();
    if (numbers) return PhotometryFormat::eulumdat;
    throw InputError(file.string() + ": neither an IES LM-63 file (no TILT= line) nor an EULUMDAT file "
                                     "(lines 2-7 are not the numbers Ityp, Isym, Mc, Dc, Ng, Dg)");
}

Photometry load_photometry(const std::filesystem::path& file, int lamp_set) {
    if (detect_photometry_format(file) == PhotometryFormat::eulumdat) return load_eulumdat(file, lamp_set);
    if (lamp_set != 1)
        throw InputError(file.string() + ": an IES file has one lamp set; lamp_set = " + std::to_string(lamp_set) +
                         " applies to EULUMDAT files");
    return load_ies(file);
}

}  // namespace luxtrace
