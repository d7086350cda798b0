#include "io/mesh/AttributedMesh.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <utility>
#include <vector>

#include "geometry/VertexNormals.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/mesh/MeshFormat.hpp"
#include "io/mesh/VtkPolyData.hpp"

namespace dfrecon {

namespace {

// Persistent properties are what OpenMesh's PLY writer emits as custom
// properties, under their names.
template <class Handle, class Range, class Values>
void addProperty(TriMesh& mesh, const std::string& name, Range elements, const Values& values) {
    Handle handle;
    mesh.add_property(handle, name);
    mesh.property(handle).set_persistent(true);
    for (auto e : elements) mesh.property(handle, e) = values[std::size_t(e.idx())];
}

// A header comment runs to the end of its line.
std::string oneLine(const std::string& text) {
    std::string line = text;
    for (char& c : line)
        if (static_cast<unsigned char>(c) < ' ') c = ' ';
    return line;
}

// The structure's header comments ("comment roi_name …", "comment
// roi_colour …"), one a line; empty without a structure.
std::string structureComments(const StructureTag& structure) {
    std::string comments;
    if (!structure.name.empty()) comments += "comment roi_name " + oneLine(structure.name) + "\n";
    if (const auto& c = structure.colour)
        comments += "comment roi_colour " + std::to_string((*c)[0]) + " " +
                    std::to_string((*c)[1]) + " " + std::to_string((*c)[2]) + "\n";
    return comments;
}

// Passes what OpenMesh writes on to `out`, with `insert` right after the
// second line. The structure's comments go after the format line:
// OpenMesh's reader finds binary data from the last token before
// end_header, which a comment there would move (io/mesh/PlyFileCheck). Streamed,
// not collected: a large surface's PLY was held three times over in memory.
// Buffered: OpenMesh writes a binary PLY one number at a time, and each
// went on to `out` as a write of its own (with OpenMesh's arrays reserved,
// toTriMesh, the head CT bone's write went from 2.8-3.0 s to 2.0-2.2 s).
// flush() before reading inserted() or `out`.
class InsertAfterFormatLine final : public std::streambuf {
  public:
    InsertAfterFormatLine(std::ostream& out, std::string insert)
        : out_(out), insert_(std::move(insert)), buffer_(kBufferBytes) {
        setp(buffer_.data(), buffer_.data() + buffer_.size());
    }
    bool inserted() const { return lines_ >= 2; }

  protected:
    int_type overflow(int_type c) override {
        if (!passOn()) return traits_type::eof();
        if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
        return c;
    }
    int sync() override { return passOn() ? 0 : -1; }

  private:
    static constexpr std::size_t kBufferBytes = 1 << 16;

    /// Writes what is buffered to out_ (the insert after its second line)
    /// and empties the buffer; false once out_ failed.
    bool passOn() {
        const char* s = pbase();
        const std::ptrdiff_t n = pptr() - pbase();
        std::ptrdiff_t done = 0;
        while (lines_ < 2 && done < n) {
            const char ch = s[done++];
            out_.put(ch);
            if (ch == '\n' && ++lines_ == 2) out_ << insert_;
        }
        if (done < n) out_.write(s + done, n - done);
        setp(buffer_.data(), buffer_.data() + buffer_.size());
        return bool(out_);
    }

    std::ostream& out_;
    std::string insert_;
    std::vector<char> buffer_;
    int lines_ = 0;
};

}  // namespace

void writeAttributedPly(std::ostream& out, const TriMesh& mesh, const MeshAttributes& attributes,
                        bool binary, bool vertexNormals) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    TriMesh copy = mesh;
    writeAttributedPly(out, std::move(copy), attributes, binary, vertexNormals);
}

void writeAttributedPly(std::ostream& out, TriMesh&& mesh, const MeshAttributes& attributes,
                        bool binary, bool vertexNormals) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    OpenMesh::IO::Options flags = OpenMesh::IO::Options::Custom;
    if (binary) flags += OpenMesh::IO::Options::Binary;
    if (vertexNormals) {
        setVertexNormals(mesh);
        flags += OpenMesh::IO::Options::VertexNormal;
    }
    if (!attributes.vertexColours.empty()) {
        mesh.request_vertex_colors();
        for (auto v : mesh.vertices()) {
            const Rgb& c = attributes.vertexColours[std::size_t(v.idx())];
            mesh.set_color(v, {c[0], c[1], c[2]});
        }
        flags += OpenMesh::IO::Options::VertexColor;
    }
    if (!attributes.faceColours.empty()) {
        mesh.request_face_colors();
        for (auto f : mesh.faces()) {
            const Rgb& c = attributes.faceColours[std::size_t(f.idx())];
            mesh.set_color(f, {c[0], c[1], c[2]});
        }
        flags += OpenMesh::IO::Options::FaceColor;
    }
    for (const auto& [name, values] : attributes.vertexScalars)
        addProperty<OpenMesh::VPropHandleT<float>>(mesh, name, mesh.vertices(), values);
    for (const auto& [name, values] : attributes.vertexLabels)
        addProperty<OpenMesh::VPropHandleT<int>>(mesh, name, mesh.vertices(), values);
    for (const auto& [name, values] : attributes.faceLabels)
        addProperty<OpenMesh::FPropHandleT<int>>(mesh, name, mesh.faces(), values);
    const std::string comments = structureComments(attributes.structure);
    if (comments.empty()) {
        if (!OpenMesh::IO::write_mesh(mesh, out, ".ply", flags, kAsciiMeshDigits))
            throw std::runtime_error("OpenMesh could not write the PLY");
        return;
    }
    InsertAfterFormatLine withComments(out, comments);
    std::ostream ply(&withComments);
    if (!OpenMesh::IO::write_mesh(mesh, ply, ".ply", flags, kAsciiMeshDigits) || !ply.flush())
        throw std::runtime_error("OpenMesh could not write the PLY");
    if (!withComments.inserted())
        throw std::runtime_error("OpenMesh wrote a PLY without a format line");
}

void writeAttributedPly(const TriMesh& mesh, const MeshAttributes& attributes,
                        const std::string& path, bool binary) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    TriMesh copy = mesh;
    writeAttributedPly(std::move(copy), attributes, path, binary);
}

void writeAttributedPly(TriMesh&& mesh, const MeshAttributes& attributes, const std::string& path,
                        bool binary) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    writeStreamAtomically(path, [&](std::ostream& out) {
        writeAttributedPly(out, std::move(mesh), attributes, binary);
    });
}

void writeAttributedPly(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path, bool binary) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    // toTriMesh keeps the points in order, so vertex arrays line up.
    std::size_t refused = 0;
    TriMesh mesh = toTriMesh(soup, &refused);
    if (refused > 0 && attributes.hasFaceData())
        throw std::invalid_argument(std::to_string(refused) +
                                    " non-manifold triangles cannot go into a PLY with face data");
    writeAttributedPly(std::move(mesh), attributes, path, binary);
}

bool isAttributedMeshPath(const std::string& path) {
    const std::optional<MeshFormat> format = meshFormatOfPath(path);
    return format == MeshFormat::Ply || format == MeshFormat::Vtk || format == MeshFormat::Vtp;
}

namespace {

void requireAttributedMeshPath(const std::string& path) {
    if (!isAttributedMeshPath(path))
        throw std::invalid_argument("'" + path +
                                    "': meshes with attributes are .ply, .vtk or .vtp");
}

void writeVtkFile(const TriangleSoup& soup, const MeshAttributes& attributes,
                  const std::string& path) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    const bool xml = meshFormatOfPath(path) == MeshFormat::Vtp;
    writeStreamAtomically(path, [&](std::ostream& out) {
        if (xml)
            writeVtkXml(out, soup, attributes);
        else
            writeVtkLegacy(out, soup, attributes);
    });
}

}  // namespace

void writeAttributedMesh(const TriMesh& mesh, const MeshAttributes& attributes,
                         const std::string& path, bool binary) {
    requireAttributedMeshPath(path);
    if (meshFormatOfPath(path) == MeshFormat::Ply)
        writeAttributedPly(mesh, attributes, path, binary);
    else
        writeVtkFile(toTriangleSoup(mesh), attributes, path);
}

void writeAttributedMesh(const TriangleSoup& soup, const MeshAttributes& attributes,
                         const std::string& path, bool binary) {
    requireAttributedMeshPath(path);
    if (meshFormatOfPath(path) == MeshFormat::Ply)
        writeAttributedPly(soup, attributes, path, binary);
    else
        writeVtkFile(soup, attributes, path);
}

}  // namespace dfrecon
