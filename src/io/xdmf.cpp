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

    static std::string dims(std::size_t a, std::size_t b) { return std::to_string(a) + ' ' + std::to_string(b); }

private:
    std::ostream& out_;
    std::string h5_;
    std::size_t T_, B_;
    bool two_sided_;
};

}  // namespace

void write_xdmf(const fs::path& result, const fs::path& xdmf) {
    std::error_code ec;
    if (fs::exists(xdmf, ec) && fs::equivalent(result, xdmf, ec))
        throw InputError(xdmf.string() + ": the XDMF file would replace the result file");
    const ResultFile r(result);
    const MeshShape mesh = r.mesh_shape();
    if (!r.has_surface_illuminance())
        throw InputError(result.string() + ": not a complete luxtrace result (mesh or /global maps missing)");
    const std::size_t V = mesh.vertices, T = mesh.triangles;
    std::vector<std::string> bands = r.bands();
    if (bands.empty()) bands.push_back("Y");
    const std::size_t B = bands.size();
    std::string scene = r.scene_name();
    if (scene.empty()) scene = result.stem().string();

    // Same folder: the bare file name, so the pair can be moved together; otherwise absolute.
    const fs::path xdir = fs::absolute(xdmf).parent_path();
    const fs::path rabs = fs::absolute(result);
    const std::string h5 = rabs.parent_path().lexically_normal() == xdir.lexically_normal()
                               ? rabs.filename().string()
                               : rabs.lexically_normal().string();

    const bool two_sided = r.surface_sides() == 2;
    std::ostringstream out;
    XdmfWriter w(out, h5, T, B, two_sided);
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"" << xml_escape(scene) << "\" GridType=\"Uniform\">\n";
    if (const auto material_names = r.material_names()) {
        std::string names;
        for (const std::string& n : *material_names) {
            if (!names.empty()) names += ',';
            names += n;
        }
        out << "      <Information Name=\"material_names\" Value=\"" << xml_escape(names) << "\"/>\n";
    }
    out << "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << T << "\">\n";
    w.hdf("        ", "/mesh/triangles", XdmfWriter::dims(T, 3), "UInt", 4);
    out << "      </Topology>\n"
        << "      <Geometry GeometryType=\"XYZ\">\n";
    w.hdf("        ", "/mesh/vertices", XdmfWriter::dims(V, 3), "Float", 8);
    out << "      </Geometry>\n";

    const std::string in = "        ";
    // Format 2: one attribute per side (_front, _back); format 1: both sides together.
    const std::vector<std::string> side_names = two_sided ? std::vector<std::string>{"_front", "_back"}
                                                          : std::vector<std::string>{""};
    for (std::size_t side = 0; side < side_names.size(); ++side)
        for (std::size_t b = 0; b < B; ++b) {
            const std::string suffix = side_names[side] + (B == 1 ? "" : "_" + bands[b]);
            w.open_attribute("illuminance" + suffix + "_lx");
            w.band_column(in, "/global/illuminance", side, b);
            w.close_attribute();
            w.open_attribute("direct" + suffix + "_lx");
            w.band_column(in, "/global/illuminance_direct", side, b);
            w.close_attribute();
            // Secondary (interreflected) light: all arrivals minus first hits.
            w.open_attribute("secondary" + suffix + "_lx");
            out << in << "<DataItem ItemType=\"Function\" Function=\"$0 - $1\" Dimensions=\"" << XdmfWriter::dims(T, 1)
                << (two_sided ? " 1" : "") << "\">\n";
            w.band_column(in + "  ", "/global/illuminance", side, b);
            w.band_column(in + "  ", "/global/illuminance_direct", side, b);
            out << in << "</DataItem>\n";
            w.close_attribute();
        }
    if (two_sided) {
        for (std::size_t side = 0; side < side_names.size(); ++side)
            for (const char* map : {"odd_even_difference", "sigma"}) {
                w.open_attribute(map + side_names[side] + "_lx");
                w.side_column(in, "/global/" + std::string(map) + "_lx", side);
                w.close_attribute();
            }
    } else if (r.has_odd_even_difference()) {
        w.open_attribute("odd_even_difference_lx");
        w.hdf(in, "/global/odd_even_difference_lx", std::to_string(T), "Float", 8);
        w.close_attribute();
    }
    w.open_attribute("area_m2");
    w.hdf(in, "/mesh/area", std::to_string(T), "Float", 8);
    w.close_attribute();
    w.open_attribute("material");
    w.hdf(in, "/mesh/material", std::to_string(T), "UInt", 4);
    w.close_attribute();
    out << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";

    const std::string text = out.str();
    write_file_atomically(xdmf, text);
}

}  // namespace luxtrace
