#include "io/VertexDataMesh.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/AtomicWrite.hpp"

namespace dfrecon {

namespace {

template <class Values>
void checkSize(const std::string& name, const Values& values, std::size_t points) {
    if (values.size() != points)
        throw std::invalid_argument("vertex data '" + name + "' has " +
                                    std::to_string(values.size()) + " values for " +
                                    std::to_string(points) + " points");
}

void checkSizes(const TriangleSoup& soup, const VertexData& data) {
    const std::size_t n = soup.points.size();
    for (const auto& [name, v] : data.scalars) checkSize(name, v, n);
    for (const auto& [name, v] : data.labels) checkSize(name, v, n);
    for (const auto& [name, v] : data.vectors) checkSize(name, v, n);
    if (!data.colours.empty()) checkSize("colours", data.colours, n);
}

}  // namespace

void writePlyWithVertexData(const TriangleSoup& soup, const VertexData& data,
                            const std::string& path) {
    checkSizes(soup, data);
    // toTriMesh keeps the points in order, so per-point arrays line up; faces
    // OpenMesh refuses (non-manifold) are left out of the PLY.
    TriMesh mesh = toTriMesh(soup);
    OpenMesh::IO::Options flags = OpenMesh::IO::Options::Binary;
    flags += OpenMesh::IO::Options::Custom;
    if (!data.colours.empty()) {
        mesh.request_vertex_colors();
        for (auto v : mesh.vertices()) {
            const auto& c = data.colours[std::size_t(v.idx())];
            mesh.set_color(v, {c[0], c[1], c[2]});
        }
        flags += OpenMesh::IO::Options::VertexColor;
    }
    // Persistent properties are what OpenMesh's PLY writer emits as custom
    // vertex properties, under their names.
    for (const auto& [name, values] : data.scalars) {
        OpenMesh::VPropHandleT<float> handle;
        mesh.add_property(handle, name);
        mesh.property(handle).set_persistent(true);
        for (auto v : mesh.vertices()) mesh.property(handle, v) = values[std::size_t(v.idx())];
    }
    for (const auto& [name, values] : data.labels) {
        OpenMesh::VPropHandleT<int> handle;
        mesh.add_property(handle, name);
        mesh.property(handle).set_persistent(true);
        for (auto v : mesh.vertices()) mesh.property(handle, v) = values[std::size_t(v.idx())];
    }
    writeAtomically(path, [&](const std::string& temporary) {
        return OpenMesh::IO::write_mesh(mesh, temporary, flags);
    });
}

void writeVtkWithVertexData(const TriangleSoup& soup, const VertexData& data,
                            const std::string& path) {
    checkSizes(soup, data);
    writeStreamAtomically(path, [&](std::ostream& out) {
        out << "# vtk DataFile Version 3.0\ndfrecon surface distance map\nASCII\n"
               "DATASET POLYDATA\nPOINTS "
            << soup.points.size() << " double\n"
            << std::setprecision(17);
        for (const Vec3& p : soup.points) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
        out << "POLYGONS " << soup.triangles.size() << ' ' << 4 * soup.triangles.size() << '\n';
        for (const auto& t : soup.triangles)
            out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
        out << "POINT_DATA " << soup.points.size() << '\n' << std::setprecision(9);
        // VTK's legacy reader takes "nan" and "inf" spelled this way.
        auto number = [&](float v) {
            if (std::isnan(v)) return std::string("nan");
            if (std::isinf(v)) return std::string(v > 0 ? "inf" : "-inf");
            std::ostringstream s;
            s << std::setprecision(9) << v;
            return s.str();
        };
        for (const auto& [name, values] : data.scalars) {
            out << "SCALARS " << name << " float 1\nLOOKUP_TABLE default\n";
            for (float v : values) out << number(v) << '\n';
        }
        for (const auto& [name, values] : data.labels) {
            out << "SCALARS " << name << " int 1\nLOOKUP_TABLE default\n";
            for (std::int32_t v : values) out << v << '\n';
        }
        for (const auto& [name, values] : data.vectors) {
            out << "VECTORS " << name << " float\n";
            for (const Vec3& v : values)
                out << number(float(v.x)) << ' ' << number(float(v.y)) << ' ' << number(float(v.z))
                    << '\n';
        }
        if (!data.colours.empty()) {
            out << "COLOR_SCALARS colour 3\n" << std::setprecision(4);
            for (const auto& c : data.colours)
                out << c[0] / 255.0 << ' ' << c[1] / 255.0 << ' ' << c[2] / 255.0 << '\n';
        }
    });
}

}  // namespace dfrecon
