#pragma once
// Triangle surfaces as the closest-primitive kernels read them: the flat
// arrays of kernels/closest_triangle_3d.cl's `Surface` (points and triangles,
// node boxes, node links, the leaf order, a ball per triangle), built from
// geometry/TriangleBvh, uploaded once and handed to any kernel that walks
// them (simplify's collapse bounds, sdm's closest primitives). Several
// hierarchies can share one set of arrays (a scene of objects), each
// searched from its own root node, with every triangle tagged by its object.
#include <string>
#include <type_traits>
#include <vector>

#include "cl/DeviceBuffer.hpp"
#include "cl/OpenCL.hpp"
#include "geometry/TriangleBvh.hpp"

namespace dfrecon {

/// The host side of the arrays. `Real4` is cl_double4 or cl_float4,
/// whichever the device computes in (ocl::withRealTypes).
template <class Real4>
struct SurfaceArrays {
    std::vector<Real4> points;
    std::vector<cl_int4> triangles;  // (a, b, c, tag), indices into points
    std::vector<Real4> nodeLo, nodeHi;
    std::vector<cl_int4> nodeLinks;  // (left, right, first, count); left < 0 for a leaf
    std::vector<cl_uint> order;      // leaf ranges, as global triangle indices
    std::vector<Real4> balls;        // per triangle: centroid, radius in w

    static Real4 real4(Vec3 p) {
        using Real = std::remove_reference_t<decltype(Real4{}.s[0])>;
        Real4 r{};
        r.s[0] = Real(p.x);
        r.s[1] = Real(p.y);
        r.s[2] = Real(p.z);
        return r;
    }

    /// Appends `bvh` and its soup, tagging its triangles with `tag`, and
    /// returns its root node's index (-1 for an empty soup). Global triangle
    /// t of the appended soup is firstTriangle + t, firstTriangle being
    /// triangles.size() before the call. O(points + triangles + nodes).
    int append(const TriangleBvh& bvh, int tag = 0) {
        const TriangleSoup& soup = bvh.soup();
        const int pointBase = int(points.size()), triangleBase = int(triangles.size()),
                  nodeBase = int(nodeLinks.size()), orderBase = int(order.size());
        for (const Vec3& p : soup.points) points.push_back(real4(p));
        for (const auto& t : soup.triangles)
            triangles.push_back(
                {{pointBase + int(t[0]), pointBase + int(t[1]), pointBase + int(t[2]), tag}});
        for (const TriangleBvh::Node& n : bvh.nodes()) {
            nodeLo.push_back(real4(n.box.lo));
            nodeHi.push_back(real4(n.box.hi));
            const bool leaf = n.left < 0;
            nodeLinks.push_back({{leaf ? -1 : nodeBase + n.left, leaf ? -1 : nodeBase + n.right,
                                  orderBase + int(n.first), int(n.count)}});
        }
        for (std::size_t t : bvh.order()) order.push_back(cl_uint(triangleBase + int(t)));
        for (const TriangleBvh::Ball& b : bvh.balls()) {
            Real4 r = real4(b.centre);
            r.s[3] = std::remove_reference_t<decltype(r.s[3])>(b.radius);
            balls.push_back(r);
        }
        return bvh.nodes().empty() ? -1 : nodeBase;
    }
};

/// The arrays on the device. Movable, not copyable.
template <class Real4>
class DeviceSurface {
  public:
    DeviceSurface() = default;
    /// Uploads `arrays`. O(size of the arrays).
    DeviceSurface(ocl::Runtime& runtime, const SurfaceArrays<Real4>& arrays)
        : points_(runtime, arrays.points),
          triangles_(runtime, arrays.triangles),
          nodeLo_(runtime, arrays.nodeLo),
          nodeHi_(runtime, arrays.nodeHi),
          nodeLinks_(runtime, arrays.nodeLinks),
          order_(runtime, arrays.order),
          balls_(runtime, arrays.balls) {}

    /// Sets a kernel's seven Surface arguments (points, triangles, node_lo,
    /// node_hi, node_links, order, balls, in that order) from argument
    /// `first` on; returns the index of the argument after them.
    cl_uint setArgs(cl::Kernel& kernel, cl_uint first) const {
        for (const cl::Buffer* buffer :
             {&points_.get(), &triangles_.get(), &nodeLo_.get(), &nodeHi_.get(), &nodeLinks_.get(),
              &order_.get(), &balls_.get()})
            kernel.setArg(first++, *buffer);
        return first;
    }

  private:
    ocl::DeviceBuffer<Real4> points_;
    ocl::DeviceBuffer<cl_int4> triangles_;
    ocl::DeviceBuffer<Real4> nodeLo_, nodeHi_;
    ocl::DeviceBuffer<cl_int4> nodeLinks_;
    ocl::DeviceBuffer<cl_uint> order_;
    ocl::DeviceBuffer<Real4> balls_;
};

/// The embedded sources of a program whose kernels walk a Surface: REAL,
/// the closest-point arithmetic and the hierarchy search, then `kernelFile`.
inline std::vector<std::string> surfaceProgramSources(const std::string& kernelFile) {
    return {"real.cl", "closest_point.cl", "closest_triangle_3d.cl", kernelFile};
}

}  // namespace dfrecon
