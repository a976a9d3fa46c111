// XDMF companion of a result file. Every attribute is a reference into the HDF5 file
// (Format="HDF"), so ParaView/VisIt read the maps in place; per-side and per-band columns of
// the [T,2,B] maps (format 2; [T,B] in format 1) are picked with HyperSlab items, the
// secondary part is a Function "$0 - $1".
// Checked with ParaView 5.11's "XDMF Reader" (all attributes, values equal to the
// datasets); its Xdmf3 readers load the mesh and the plain datasets but skip the
// HyperSlab and Function attributes.
#include "luxtrace/io/xdmf.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/io/result_data.hpp"

#include <unistd.h>
#include <fstream>
#include <optional>
#include <sstream>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&apos;"; break;
        default: out += c;
        }
    }
    return out;
}

// Writes the DataItems of one document; `h5` is the file reference as it appears
// before the ':' of each HDF DataItem.
class XdmfWriter {
public:
    // two_sided: the maps have format 2's side axis.
    XdmfWriter(std::ostream& out, std::string h5, std::size_t triangles, std::size_t bands, bool two_sided)
        : out_(out), h5_(xml_escape(h5)), T_(triangles), B_(bands), two_sided_(two_sided) {}

    // A whole dataset: `dims` as XDMF writes them ("T 3"), type "Float"/"UInt", bytes.
    void hdf(const std::string& indent, const std::string& path, const std::string& dims, const char* type,
             int precision) {
        out_ << indent << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"" << type << "\" Precision=\""
             << precision << "\" Format=\"HDF\">" << h5_ << ':' << path << "</DataItem>\n";
    }
    // Side `side`, band `band` of a float64 [T,2,B] map as a [T,1,1] item; of a format-1
    // [T,B] map, column `band` (the dataset itself when B = 1).
    void band_column(const std::string& indent, const std::string& path, std::size_t side, std::size_t band) {
        if (two_sided_) {
            out_ << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << T_ << " 1 1\" Type=\"HyperSlab\">\n"
                 << indent << "  <DataItem Dimensions=\"3 3\" NumberType=\"UInt\" Format=\"XML\">0 " << side << ' '
                 << band << " 1 1 1 " << T_ << " 1 1</DataItem>\n";
            hdf(indent + "  ", path, std::to_string(T_) + " 2 " + std::to_string(B_), "Float", 8);
            out_ << indent << "</DataItem>\n";
            return;
        }
        if (B_ == 1) {
            hdf(indent, path, dims(T_, 1), "Float", 8);
            return;
        }
        out_ << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << dims(T_, 1) << "\" Type=\"HyperSlab\">\n"
             << indent << "  <DataItem Dimensions=\"3 2\" NumberType=\"UInt\" Format=\"XML\">0 " << band << " 1 1 "
             << T_ << " 1</DataItem>\n";
        hdf(indent + "  ", path, dims(T_, B_), "Float", 8);
        out_ << indent << "</DataItem>\n";
    }
    // Side `side` of a float64 [T,2] map as a [T,1] item.
    void side_column(const std::string& indent, const std::string& path, std::size_t side) {
        out_ << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << dims(T_, 1) << "\" Type=\"HyperSlab\">\n"
             << indent << "  <DataItem Dimensions=\"3 2\" NumberType=\"UInt\" Format=\"XML\">0 " << side << " 1 1 "
             << T_ << " 1</DataItem>\n";
        hdf(indent + "  ", path, dims(T_, 2), "Float", 8);
        out_ << indent << "</DataItem>\n";
    }
    void open_attribute(const std::string& name) {
        out_ << "      <Attribute Name=\"" << xml_escape(name) << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    }
    void close_attribute() { out_ << "      </Attribute>\n"; }

    // A per-triangle dataset `path` [T] as attribute `name`.
    void triangle_attribute(const std::string& name, const std::string& path, const char* type, int precision) {
        open_attribute(name);
        hdf(kAttributeIndent, path, std::to_string(T_), type, precision);
        close_attribute();
    }
    // Side `side`, band `band` of the maps as three attributes: all arrivals, first hits
    // (direct), and the secondary (interreflected) light, all arrivals minus first hits.
    void illuminance_attributes(const std::string& suffix, std::size_t side, std::size_t band) {
        const std::string& in = kAttributeIndent;
        open_attribute("illuminance" + suffix + "_lx");
        band_column(in, "/global/illuminance", side, band);
        close_attribute();
        open_attribute("direct" + suffix + "_lx");
        band_column(in, "/global/illuminance_direct", side, band);
        close_attribute();
        open_attribute("secondary" + suffix + "_lx");
        out_ << in << "<DataItem ItemType=\"Function\" Function=\"$0 - $1\" Dimensions=\"" << dims(T_, 1)
             << (two_sided_ ? " 1" : "") << "\">\n";
        band_column(in + "  ", "/global/illuminance", side, band);
        band_column(in + "  ", "/global/illuminance_direct", side, band);
        out_ << in << "</DataItem>\n";
        close_attribute();
    }

    static std::string dims(std::size_t a, std::size_t b) { return std::to_string(a) + ' ' + std::to_string(b); }
    inline static const std::string kAttributeIndent = "        ";  // of an attribute's DataItem

private:
    std::ostream& out_;
    std::string h5_;
    std::size_t T_, B_;
    bool two_sided_;
};

// Same folder: the bare file name, so the pair can be moved together; otherwise absolute.
std::string h5_reference(const fs::path& result, const fs::path& xdmf) {
    const fs::path xdir = fs::absolute(xdmf).parent_path();
    const fs::path rabs = fs::absolute(result);
    return rabs.parent_path().lexically_normal() == xdir.lexically_normal() ? rabs.filename().string()
                                                                            : rabs.lexically_normal().string();
}

void write_grid_header(std::ostream& out, const std::string& scene,
                       const std::optional<std::vector<std::string>>& material_names) {
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"" << xml_escape(scene) << "\" GridType=\"Uniform\">\n";
    if (material_names) {
        std::string names;
        for (const std::string& n : *material_names) {
            if (!names.empty()) names += ',';
            names += n;
        }
        out << "      <Information Name=\"material_names\" Value=\"" << xml_escape(names) << "\"/>\n";
    }
}

void write_mesh(std::ostream& out, XdmfWriter& w, const MeshShape& mesh) {
    const std::size_t V = mesh.vertices, T = mesh.triangles;
    out << "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << T << "\">\n";
    w.hdf("        ", "/mesh/triangles", XdmfWriter::dims(T, 3), "UInt", 4);
    out << "      </Topology>\n"
        << "      <Geometry GeometryType=\"XYZ\">\n";
    w.hdf("        ", "/mesh/vertices", XdmfWriter::dims(V, 3), "Float", 8);
    out << "      </Geometry>\n";
}

// The surface maps as cell attributes. Format 2: one attribute per side (_front, _back);
// format 1: both sides together.
void write_maps(XdmfWriter& w, const ResultFile& r, const std::vector<std::string>& bands, bool two_sided) {
    const std::size_t B = bands.size();
    const std::vector<std::string> side_names = two_sided ? std::vector<std::string>{"_front", "_back"}
                                                          : std::vector<std::string>{""};
    for (std::size_t side = 0; side < side_names.size(); ++side)
        for (std::size_t b = 0; b < B; ++b)
            w.illuminance_attributes(side_names[side] + (B == 1 ? "" : "_" + bands[b]), side, b);
    if (two_sided) {
        for (std::size_t side = 0; side < side_names.size(); ++side)
            for (const char* map : {"odd_even_difference", "sigma"}) {
                w.open_attribute(map + side_names[side] + "_lx");
                w.side_column(XdmfWriter::kAttributeIndent, "/global/" + std::string(map) + "_lx", side);
                w.close_attribute();
            }
    } else if (r.has_odd_even_difference()) {
        w.triangle_attribute("odd_even_difference_lx", "/global/odd_even_difference_lx", "Float", 8);
    }
}

}  // namespace

void write_xdmf(const fs::path& result, const fs::path& xdmf) {
    std::error_code ec;
    if (fs::exists(xdmf, ec) && fs::equivalent(result, xdmf, ec))
        throw InputError(xdmf.string() + ": the XDMF file would replace the result file");
    const ResultFile r(result);
    const MeshShape mesh = r.mesh_shape();
    if (!r.has_surface_illuminance())
        throw InputError(result.string() + ": not a complete luxtrace result (mesh or /global maps missing)");
    std::vector<std::string> bands = r.bands();
    if (bands.empty()) bands.push_back("Y");
    std::string scene = r.scene_name();
    if (scene.empty()) scene = result.stem().string();

    const std::string h5 = h5_reference(result, xdmf);
    const bool two_sided = r.surface_sides() == 2;
    std::ostringstream out;
    XdmfWriter w(out, h5, mesh.triangles, bands.size(), two_sided);
    write_grid_header(out, scene, r.material_names());
    write_mesh(out, w, mesh);
    write_maps(w, r, bands, two_sided);
    w.triangle_attribute("area_m2", "/mesh/area", "Float", 8);
    w.triangle_attribute("material", "/mesh/material", "UInt", 4);
    out << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";

    const std::string text = out.str();
    write_file_atomically(xdmf, text);
}

}  // namespace luxtrace
