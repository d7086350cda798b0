#include "sdm/ClosestPrimitives.hpp"

#include <array>
#include <unordered_map>

#include "cl/DeviceBuffer.hpp"
#include "cl/Precision.hpp"
#include "field/DeviceSurface.hpp"

namespace dfrecon {

namespace {

bool isCandidate(const DistanceQuery& query, std::size_t own, std::size_t object) {
    return object != own && (query.target < 0 || object == std::size_t(query.target));
}

double bandSquared(const DistanceQuery& query) {
    return query.maxDistanceMm * query.maxDistanceMm;
}

Vec3 centroid(const TriangleSoup& soup, std::size_t t) {
    const auto& tri = soup.triangles[t];
    return (1.0 / 3.0) * (soup.points[tri[0]] + soup.points[tri[1]] + soup.points[tri[2]]);
}

// The full answer once the nearest triangle is known: the closest point,
// its feature, and the sign from that feature's pseudo-normal.
ClosestPrimitive describe(const SurfaceScene& scene, std::size_t object, std::size_t triangle,
                          Vec3 p) {
    const TriangleSoup& soup = scene.object(object);
    const auto& tri = soup.triangles[triangle];
    ClosestPrimitive answer;
    answer.object = std::int32_t(object);
    answer.triangle = std::uint32_t(triangle);
    answer.point = closestPointOnTriangle(p, soup.points[tri[0]], soup.points[tri[1]],
                                          soup.points[tri[2]], &answer.feature);
    const Vec3 away = p - answer.point;
    answer.distanceMm = length(away);
    if (scene.closed(object) && dot(away, scene.pseudoNormal(object, triangle, answer.feature)) < 0)
        answer.distanceMm = -answer.distanceMm;
    return answer;
}

struct Found {
    std::size_t object = SIZE_MAX, triangle = SIZE_MAX;
    double distance2 = INFINITY;
};

// Each sample's search starts from the nearest triangles found for its own
// triangle's centre and corners: the best of them bounds the search.
constexpr int kHints = 4;
using Hints = std::array<Found, kHints>;

// The bounded search the kernel makes: the hints first, then each
// candidate object's hierarchy with the best distance so far as its bound.
Found searchObjects(const SurfaceScene& scene, Vec3 p, std::size_t own, const Hints& hints,
                    const DistanceQuery& query) {
    Found best;
    best.distance2 = bandSquared(query);
    for (const Found& hint : hints) {
        if (hint.object == SIZE_MAX || !isCandidate(query, own, hint.object)) continue;
        const auto& soup = scene.object(hint.object);
        const auto& tri = soup.triangles[hint.triangle];
        const Vec3 q = closestPointOnTriangle(p, soup.points[tri[0]], soup.points[tri[1]],
                                              soup.points[tri[2]]);
        if (dot(p - q, p - q) < best.distance2)
            best = {hint.object, hint.triangle, dot(p - q, p - q)};
    }
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        if (!isCandidate(query, own, o)) continue;
        const TriangleBvh::Nearest n = scene.bvh(o).nearestWithin(p, best.distance2);
        if (n.triangle != SIZE_MAX) best = {o, n.triangle, n.distance2};
    }
    return best;
}

std::uint64_t triangleKey(std::size_t object, std::size_t triangle) {
    return (std::uint64_t(object) << 32) | std::uint64_t(triangle);
}

// Where the hints are looked for: the centre of every triangle that holds a
// sample and each of its corners, every point once (corners are shared by
// about six triangles), and which four of them serve each sample.
struct HintPlan {
    std::vector<SurfaceSample> points;
    std::vector<std::array<std::uint32_t, kHints>> ofSample;
};

HintPlan planHints(const SurfaceScene& scene, const std::vector<SurfaceSample>& samples) {
    HintPlan plan;
    std::unordered_map<std::uint64_t, std::array<std::uint32_t, kHints>> ofTriangle;
    std::unordered_map<std::uint64_t, std::uint32_t> ofCorner;
    plan.ofSample.reserve(samples.size());
    for (const SurfaceSample& s : samples) {
        const auto [it, fresh] = ofTriangle.emplace(triangleKey(s.object, s.triangle),
                                                    std::array<std::uint32_t, kHints>{});
        if (fresh) {
            const TriangleSoup& soup = scene.object(s.object);
            it->second[0] = std::uint32_t(plan.points.size());
            plan.points.push_back({centroid(soup, s.triangle), s.object, s.triangle});
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = soup.triangles[s.triangle][std::size_t(k)];
                const auto [corner, first] =
                    ofCorner.emplace(triangleKey(s.object, v), std::uint32_t(plan.points.size()));
                if (first) plan.points.push_back({soup.points[v], s.object, s.triangle});
                it->second[std::size_t(k) + 1] = corner->second;
            }
        }
        plan.ofSample.push_back(it->second);
    }
    return plan;
}

}  // namespace

std::vector<ClosestPrimitive> closestPrimitivesReference(const SurfaceScene& scene,
                                                         const std::vector<SurfaceSample>& samples,
                                                         const DistanceQuery& query) {
    const HintPlan plan = planHints(scene, samples);
    std::vector<Found> hintAnswers(plan.points.size());
    for (std::size_t k = 0; k < plan.points.size(); ++k)
        hintAnswers[k] =
            searchObjects(scene, plan.points[k].point, plan.points[k].object, Hints{}, query);
    std::vector<ClosestPrimitive> answers(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const SurfaceSample& s = samples[k];
        Hints hints;
        for (int h = 0; h < kHints; ++h)
            hints[std::size_t(h)] = hintAnswers[plan.ofSample[k][std::size_t(h)]];
        const Found best = searchObjects(scene, s.point, s.object, hints, query);
        if (best.object != SIZE_MAX)
            answers[k] = describe(scene, best.object, best.triangle, s.point);
    }
    return answers;
}

std::vector<ClosestPrimitive> closestPrimitivesBruteForce(const SurfaceScene& scene,
                                                          const std::vector<SurfaceSample>& samples,
                                                          const DistanceQuery& query) {
    std::vector<ClosestPrimitive> answers(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const SurfaceSample& s = samples[k];
        Found best;
        best.distance2 = bandSquared(query);
        for (std::size_t o = 0; o < scene.objectCount(); ++o) {
            if (!isCandidate(query, s.object, o)) continue;
            const TriangleSoup& soup = scene.object(o);
            for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
                const auto& tri = soup.triangles[t];
                const Vec3 q = closestPointOnTriangle(s.point, soup.points[tri[0]],
                                                      soup.points[tri[1]], soup.points[tri[2]]);
                const double d2 = dot(s.point - q, s.point - q);
                if (d2 < best.distance2) best = {o, t, d2};
            }
        }
        if (best.object != SIZE_MAX)
            answers[k] = describe(scene, best.object, best.triangle, s.point);
    }
    return answers;
}

// --- OpenCL ------------------------------------------------------------------

namespace {

// The interface both precisions implement.
struct DeviceScene {
    virtual ~DeviceScene() = default;
    virtual std::vector<ClosestPrimitive> run(const std::vector<SurfaceSample>& samples,
                                              const DistanceQuery& query) = 0;
};

template <class Real, class Real4>
class DeviceSceneT final : public DeviceScene {
  public:
    DeviceSceneT(ocl::Runtime& runtime, const SurfaceScene& scene)
        : runtime_(runtime), scene_(scene) {
        SurfaceArrays<Real4> arrays;
        std::vector<Real4> normals;
        std::vector<cl_uchar> closed;
        for (std::size_t o = 0; o < scene.objectCount(); ++o) {
            firstTriangle_.push_back(arrays.triangles.size());
            roots_.push_back(arrays.append(scene.bvh(o), int(o)));
            closed.push_back(scene.closed(o) ? 1 : 0);
            for (std::size_t t = 0; t < scene.object(o).triangles.size(); ++t)
                for (int f = 0; f < 7; ++f)
                    normals.push_back(
                        SurfaceArrays<Real4>::real4(scene.pseudoNormal(o, t, TriangleFeature(f))));
        }
        objectOfTriangle_.reserve(arrays.triangles.size());
        for (const cl_int4& t : arrays.triangles) objectOfTriangle_.push_back(std::size_t(t.s[3]));
        surface_ = DeviceSurface<Real4>(runtime, arrays);
        objectRoot_ = ocl::DeviceBuffer<cl_int>(runtime, roots_);
        normals_ = ocl::DeviceBuffer<Real4>(runtime, normals);
        closed_ = ocl::DeviceBuffer<cl_uchar>(runtime, closed);
        program_ = &runtime.program(surfaceProgramSources("surface_distance.cl"),
                                    ocl::realOptions<Real>());
    }

    std::vector<ClosestPrimitive> run(const std::vector<SurfaceSample>& samples,
                                      const DistanceQuery& query) override {
        // Pass 1: the nearest triangles to the centres and corners of the
        // samples' triangles, the hints that bound pass 2 from its start.
        const HintPlan plan = planHints(scene_, samples);
        const cl_uint4 none{{CL_UINT_MAX, CL_UINT_MAX, CL_UINT_MAX, CL_UINT_MAX}};
        const Launch hints =
            launch(plan.points, std::vector<cl_uint4>(plan.points.size(), none), query);
        std::vector<cl_uint4> sampleHints(samples.size());
        for (std::size_t k = 0; k < samples.size(); ++k)
            for (int h = 0; h < kHints; ++h)
                sampleHints[k].s[h] = hints.nearest[plan.ofSample[k][std::size_t(h)]];
        const Launch found = launch(samples, sampleHints, query);

        std::vector<ClosestPrimitive> answers(samples.size());
        for (std::size_t k = 0; k < samples.size(); ++k) {
            const cl_uint t = found.nearest[k];
            if (t == CL_UINT_MAX) continue;
            ClosestPrimitive& a = answers[k];
            a.object = std::int32_t(objectOfTriangle_[t]);
            a.triangle = std::uint32_t(t - firstTriangle_[objectOfTriangle_[t]]);
            a.distanceMm = double(found.distance[k]);
            a.feature = TriangleFeature(found.feature[k]);
            a.point = {double(found.closest[k].s[0]), double(found.closest[k].s[1]),
                       double(found.closest[k].s[2])};
        }
        return answers;
    }

  private:
    struct Launch {
        std::vector<cl_uint> nearest;
        std::vector<Real> distance;
        std::vector<cl_uchar> feature;
        std::vector<Real4> closest;
    };

    Launch launch(const std::vector<SurfaceSample>& samples, const std::vector<cl_uint4>& hints,
                  const DistanceQuery& query) {
        Launch out;
        if (samples.empty()) return out;
        std::vector<Real4> points(samples.size());
        std::vector<cl_uint> objects(samples.size());
        for (std::size_t k = 0; k < samples.size(); ++k) {
            points[k] = SurfaceArrays<Real4>::real4(samples[k].point);
            objects[k] = samples[k].object;
        }
        ocl::DeviceBuffer<Real4> dPoints(runtime_, points);
        ocl::DeviceBuffer<cl_uint> dObjects(runtime_, objects);
        ocl::DeviceBuffer<cl_uint4> dHints(runtime_, hints);
        ocl::DeviceBuffer<cl_uint> dNearest(runtime_, samples.size(), CL_MEM_WRITE_ONLY);
        ocl::DeviceBuffer<Real> dDistance(runtime_, samples.size(), CL_MEM_WRITE_ONLY);
        ocl::DeviceBuffer<cl_uchar> dFeature(runtime_, samples.size(), CL_MEM_WRITE_ONLY);
        ocl::DeviceBuffer<Real4> dClosest(runtime_, samples.size(), CL_MEM_WRITE_ONLY);
        try {
            cl::Kernel kernel(*program_, "closest_primitive");
            cl_uint a = 0;
            kernel.setArg(a++, dPoints.get());
            kernel.setArg(a++, dObjects.get());
            kernel.setArg(a++, dHints.get());
            kernel.setArg(a++, cl_uint(samples.size()));
            a = surface_.setArgs(kernel, a);
            kernel.setArg(a++, objectRoot_.get());
            kernel.setArg(a++, cl_uint(roots_.size()));
            kernel.setArg(a++, normals_.get());
            kernel.setArg(a++, closed_.get());
            kernel.setArg(a++, cl_int(query.target));
            kernel.setArg(a++, Real(bandSquared(query)));
            kernel.setArg(a++, dDistance.get());
            kernel.setArg(a++, dNearest.get());
            kernel.setArg(a++, dFeature.get());
            kernel.setArg(a++, dClosest.get());
            runtime_.queue().enqueueNDRangeKernel(
                kernel, cl::NullRange, cl::NDRange(ocl::roundUp(samples.size(), ocl::kGroupSize1D)),
                cl::NDRange(ocl::kGroupSize1D));
        } catch (const cl::Error& e) {
            throw ocl::toClError(e, "surface_distance.cl");
        }
        out.nearest = dNearest.download(runtime_);
        out.distance = dDistance.download(runtime_);
        out.feature = dFeature.download(runtime_);
        out.closest = dClosest.download(runtime_);
        return out;
    }

    ocl::Runtime& runtime_;
    const SurfaceScene& scene_;
    const cl::Program* program_ = nullptr;
    std::vector<std::size_t> firstTriangle_, objectOfTriangle_;
    std::vector<cl_int> roots_;
    DeviceSurface<Real4> surface_;
    ocl::DeviceBuffer<Real4> normals_;
    ocl::DeviceBuffer<cl_int> objectRoot_;
    ocl::DeviceBuffer<cl_uchar> closed_;
};

}  // namespace

struct ClosestPrimitiveKernel::Impl {
    std::unique_ptr<DeviceScene> device;
    double extentMm = 0;
    bool doublePrecision = true;
};

ClosestPrimitiveKernel::ClosestPrimitiveKernel(ocl::Runtime& runtime, const SurfaceScene& scene)
    : impl_(std::make_unique<Impl>()) {
    impl_->doublePrecision = runtime.device().doublePrecision;
    impl_->device = ocl::withRealTypes(
        impl_->doublePrecision, [&](auto real, auto real4) -> std::unique_ptr<DeviceScene> {
            return std::make_unique<DeviceSceneT<decltype(real), decltype(real4)>>(runtime, scene);
        });
    Box3 box;
    for (std::size_t o = 0; o < scene.objectCount(); ++o)
        for (const Vec3& p : scene.object(o).points) box.add(p);
    impl_->extentMm = length(box.hi - box.lo);
}

ClosestPrimitiveKernel::~ClosestPrimitiveKernel() = default;

std::vector<ClosestPrimitive> ClosestPrimitiveKernel::run(const std::vector<SurfaceSample>& samples,
                                                          const DistanceQuery& query) {
    return impl_->device->run(samples, query);
}

double ClosestPrimitiveKernel::toleranceMm() const {
    return (impl_->doublePrecision ? 1e-12 : 1e-6) * impl_->extentMm;
}

}  // namespace dfrecon
