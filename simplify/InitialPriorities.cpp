#include "simplify/InitialPriorities.hpp"

#include <algorithm>

#include "cl/DeviceBuffer.hpp"
#include "cl/Precision.hpp"
#include "field/DeviceSurface.hpp"
#include "simplify/CollapseBound.hpp"

namespace dfrecon {

namespace {

bool isWanted(const std::vector<bool>* wanted, TriMesh::HalfedgeHandle h) {
    return !wanted || (std::size_t(h.idx()) < wanted->size() && (*wanted)[std::size_t(h.idx())]);
}

template <class Real, class Real4>
std::vector<float> runBatch(ocl::Runtime& runtime, const TriMesh& mesh,
                            const DeviationSurface& original, double maxErrorMm,
                            const std::vector<bool>* wanted) {
    // The wanted halfedges, packed: work-item k evaluates halfedge index[k].
    std::vector<cl_int2> halfedges;
    std::vector<std::size_t> index;
    for (auto h : mesh.halfedges()) {
        if (!isWanted(wanted, h)) continue;
        halfedges.push_back({{mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx()}});
        index.push_back(std::size_t(h.idx()));
    }
    std::vector<float> result(mesh.n_halfedges(), -1.0f);
    if (halfedges.empty()) return result;
    using Arrays = SurfaceArrays<Real4>;
    std::vector<Real4> meshPoints(mesh.n_vertices());
    std::vector<cl_uint> ringFirst{0};
    std::vector<cl_int4> ringFaces;
    for (auto v : mesh.vertices()) {
        meshPoints[std::size_t(v.idx())] = Arrays::real4(toVec3(mesh.point(v)));
        for (auto f : mesh.vf_range(v)) {
            cl_int4 face{{0, 0, 0, 0}};
            int k = 0;
            for (auto u : mesh.fv_range(f)) face.s[k++] = u.idx();
            ringFaces.push_back(face);
        }
        ringFirst.push_back(cl_uint(ringFaces.size()));
    }
    Arrays arrays;
    arrays.append(original.bvh);
    const DeviceSurface<Real4> surface(runtime, arrays);
    const VertexFans& fans = original.fans;
    std::vector<Real4> fanNormals;
    for (const Vec3& n : fans.sectorNormals()) fanNormals.push_back(Arrays::real4(n));
    ocl::DeviceBuffer<cl_uint> dFanFirst(runtime, fans.first());
    ocl::DeviceBuffer<cl_uint> dFanRing(runtime, fans.ring());
    ocl::DeviceBuffer<Real4> dFanNormals(runtime, fanNormals);

    ocl::DeviceBuffer<cl_int2> dHalfedges(runtime, halfedges);
    ocl::DeviceBuffer<Real4> dMeshPoints(runtime, meshPoints);
    ocl::DeviceBuffer<cl_uint> dRingFirst(runtime, ringFirst);
    ocl::DeviceBuffer<cl_int4> dRingFaces(runtime, ringFaces);
    ocl::DeviceBuffer<cl_float> priority(runtime, halfedges.size(), CL_MEM_WRITE_ONLY);
    std::vector<std::string> sources = surfaceProgramSources("collapse_bound.cl");
    sources.insert(sources.end() - 1, "straddle_bound.cl");
    sources.insert(sources.end() - 1, "fan_bound.cl");
    const cl::Program& program = runtime.program(sources, ocl::realOptions<Real>());
    const DeviationLimits limits{maxErrorMm};
    try {
        cl::Kernel kernel(program, "collapse_bound");
        cl_uint a = 0;
        kernel.setArg(a++, dHalfedges.get());
        kernel.setArg(a++, cl_uint(halfedges.size()));
        kernel.setArg(a++, dMeshPoints.get());
        kernel.setArg(a++, dRingFirst.get());
        kernel.setArg(a++, dRingFaces.get());
        a = surface.setArgs(kernel, a);
        kernel.setArg(a++, dFanFirst.get());
        kernel.setArg(a++, dFanRing.get());
        kernel.setArg(a++, dFanNormals.get());
        kernel.setArg(a++, Real(limits.limitMm));
        kernel.setArg(a++, Real(limits.finestFraction * limits.limitMm));
        kernel.setArg(a++, Real(kSliverAreaRatio));
        kernel.setArg(a++, priority.get());
        runtime.queue().enqueueNDRangeKernel(
            kernel, cl::NullRange, cl::NDRange(ocl::roundUp(halfedges.size(), ocl::kGroupSize1D)),
            cl::NDRange(ocl::kGroupSize1D));
    } catch (const cl::Error& e) {
        throw ocl::toClError(e, "collapse_bound.cl");
    }
    std::vector<float> packed = priority.download(runtime);
    if (sizeof(Real) < 8) {
        Box3 box;
        for (const Vec3& p : original.soup().points) box.add(p);
        const float slack = float(1e-6 * length(box.hi - box.lo));
        for (float& p : packed)
            if (p >= 0) p = p + slack > float(maxErrorMm) ? -1.0f : p + slack;
    }
    for (std::size_t k = 0; k < packed.size(); ++k) result[index[k]] = packed[k];
    return result;
}

}  // namespace

std::vector<float> initialPriorities(ocl::Runtime& runtime, const TriMesh& mesh,
                                     const DeviationSurface& original, double maxErrorMm,
                                     const std::vector<bool>* wanted) {
    if (mesh.n_halfedges() == 0) return {};
    return ocl::withRealTypes(runtime.device().doublePrecision, [&](auto real, auto real4) {
        return runBatch<decltype(real), decltype(real4)>(runtime, mesh, original, maxErrorMm,
                                                         wanted);
    });
}

std::vector<float> initialPrioritiesReference(const TriMesh& mesh, const DeviationSurface& original,
                                              double maxErrorMm, const std::vector<bool>* wanted) {
    std::vector<float> result(mesh.n_halfedges(), -1.0f);
    std::vector<NewTriangle> created;
    const DeviationLimits limits{maxErrorMm};
    for (auto h : mesh.halfedges()) {
        if (!isWanted(wanted, h) || !trianglesAfterCollapse(mesh, h, created)) continue;
        result[std::size_t(h.idx())] = surfaceDeviation(created, original, limits);
    }
    return result;
}

}  // namespace dfrecon
