#include "field/ClosestPrimitives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cl/DeviceBuffer.hpp"
#include "cl/Precision.hpp"
#include "field/DeviceSurface.hpp"

namespace dfrecon {

namespace tangent {
using closest::dot3;
using std::clamp;
using std::sqrt;
#define REAL double
#define REAL4 Vec3
#define TANGENT_FN inline
#include "kernels/tangent_bound.cl"
#undef TANGENT_FN
#undef REAL4
#undef REAL
}  // namespace tangent

namespace {

// Candidates a source triangle lists at most; beyond, its samples search the
// hierarchies instead (a few source triangles near contact, where many
// target triangles are equally near).
constexpr std::size_t kCandidateCapacity = 64;
// Source triangles per launch: bounds the lists' memory (36 or 20 bytes per
// entry, about 38 MB in double precision) on meshes of millions of
// triangles.
constexpr std::size_t kSourcesPerLaunch = std::size_t(1) << 14;
// Free points per launch of closest_primitive_at.
constexpr std::size_t kPointsPerLaunch = std::size_t(1) << 18;
// The own object of a point on none: every object is a candidate.
constexpr std::size_t kNoObject = SIZE_MAX;

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

// The nearest triangle of the candidate objects to p, strictly nearer than
// `best` (a hint, or none): each object's hierarchy with the best distance
// so far as its bound, as the kernel's fallback search does.
Found searchObjects(const SurfaceScene& scene, Vec3 p, std::size_t own, Found best,
                    const DistanceQuery& query) {
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        if (!isCandidate(query, own, o)) continue;
        const TriangleBvh::Nearest n = scene.bvh(o).nearestWithin(p, best.distance2);
        if (n.triangle != SIZE_MAX) best = {o, n.triangle, n.distance2};
    }
    return best;
}

double triangleDistance2(const SurfaceScene& scene, std::size_t object, std::size_t triangle,
                         Vec3 p) {
    const TriangleSoup& soup = scene.object(object);
    const auto& tri = soup.triangles[triangle];
    const Vec3 q =
        closestPointOnTriangle(p, soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]);
    return dot(p - q, p - q);
}

// Starts a search from `hint` (the triangle nearest the sample's triangle's
// centre) when it is a candidate within the band.
Found startFrom(const SurfaceScene& scene, Vec3 p, std::size_t own, const Found& hint,
                const DistanceQuery& query) {
    Found best;
    best.distance2 = bandSquared(query);
    if (hint.object == SIZE_MAX || !isCandidate(query, own, hint.object)) return best;
    const double d2 = triangleDistance2(scene, hint.object, hint.triangle, p);
    if (d2 < best.distance2) best = {hint.object, hint.triangle, d2};
    return best;
}

// The rounding allowance of the tangent-bound culling (kernels/tangent_bound.cl)
// for a scene `extentMm` across computed in type Real: far above the
// rounding of coordinates that size; samples farther than half of it from
// their own triangle are searched without the culled list.
template <class Real>
double cullSlackMm(double extentMm) {
    return std::max(64 * double(std::numeric_limits<Real>::epsilon()), 1e-9) * (extentMm + 1);
}

double extentOf(const SurfaceScene& scene) {
    Box3 box;
    for (std::size_t o = 0; o < scene.objectCount(); ++o)
        for (const Vec3& p : scene.object(o).points) box.add(p);
    return box.lo.x <= box.hi.x ? length(box.hi - box.lo) : 0.0;
}

// The triangles of the candidate objects that can be nearest to some sample
// of one source triangle, each with its tangent bound at the centre, when
// there are at most kCandidateCapacity; the kernel's source_candidates.
struct Candidate {
    std::size_t object, triangle;
    tangent::TangentBound bound;
};
struct SourceCandidates {
    Found centre;  // the triangle nearest to the centre: the search's first bound
    std::vector<Candidate> list;
    bool overflow = false;  // too many: its samples search the hierarchies
};

SourceCandidates sourceCandidates(const SurfaceScene& scene, std::size_t own, std::size_t triangle,
                                  const DistanceQuery& query, double slackMm) {
    const TriangleSoup& soup = scene.object(own);
    const auto& tri = soup.triangles[triangle];
    const Vec3 v0 = soup.points[tri[0]], v1 = soup.points[tri[1]], v2 = soup.points[tri[2]];
    const Vec3 c = centroid(soup, triangle);  // as the kernel computes it
    SourceCandidates source;
    Found none;
    none.distance2 = bandSquared(query);
    source.centre = searchObjects(scene, c, own, none, query);
    double u0 = INFINITY, u1 = INFINITY, u2 = INFINITY;
    if (source.centre.object != SIZE_MAX) {
        const Found& t1 = source.centre;
        u0 = std::sqrt(triangleDistance2(scene, t1.object, t1.triangle, v0));
        u1 = std::sqrt(triangleDistance2(scene, t1.object, t1.triangle, v1));
        u2 = std::sqrt(triangleDistance2(scene, t1.object, t1.triangle, v2));
    }
    const double band = query.maxDistanceMm;
    const auto excludes = [&](const tangent::TangentBound& bound) {
        return tangent::tangent_excludes(bound, v0, v1, v2, u0, u1, u2, band, slackMm) != 0;
    };
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        if (!isCandidate(query, own, o)) continue;
        const TriangleBvh& bvh = scene.bvh(o);
        if (bvh.nodes().empty()) continue;
        // Depth first, left before right, as the kernel walks.
        std::vector<int> stack{0};
        while (!stack.empty()) {
            const TriangleBvh::Node& node = bvh.nodes()[std::size_t(stack.back())];
            stack.pop_back();
            if (excludes(tangent::tangent_bound_of_box(c, node.box.lo, node.box.hi))) continue;
            if (node.left >= 0) {
                stack.push_back(node.right);
                stack.push_back(node.left);
                continue;
            }
            for (std::size_t k = 0; k < node.count; ++k) {
                const std::size_t t = bvh.order()[node.first + k];
                const auto& target = scene.object(o).triangles[t];
                const TriangleSoup& other = scene.object(o);
                const Vec3 q = closestPointOnTriangle(
                    c, other.points[target[0]], other.points[target[1]], other.points[target[2]]);
                const tangent::TangentBound bound = tangent::tangent_bound(c, q);
                if (excludes(bound)) continue;
                if (source.list.size() == kCandidateCapacity) {
                    source.overflow = true;
                    source.list.clear();
                    return source;
                }
                source.list.push_back({o, t, bound});
            }
        }
    }
    return source;
}

// The nearest triangle to sample p of source triangle `triangle` of `own`:
// the centre's nearest first, then the listed candidates whose bound at p
// does not rule them out, or the hierarchies when the list overflowed or p
// is off its triangle.
Found searchSample(const SurfaceScene& scene, const SurfaceSample& sample,
                   const SourceCandidates& source, const DistanceQuery& query, double slackMm) {
    const Vec3 p = sample.point;
    const std::size_t own = sample.object, triangle = sample.triangle;
    Found best = startFrom(scene, p, own, source.centre, query);
    const bool onTriangle = triangleDistance2(scene, own, triangle, p) <= 0.25 * slackMm * slackMm;
    if (source.overflow || !onTriangle) return searchObjects(scene, p, own, best, query);
    for (const Candidate& candidate : source.list) {
        const double lower = tangent::tangent_lower(candidate.bound, p) - slackMm;
        if (lower > 0 && lower * lower >= best.distance2) continue;
        const double d2 = triangleDistance2(scene, candidate.object, candidate.triangle, p);
        if (d2 < best.distance2) best = {candidate.object, candidate.triangle, d2};
    }
    return best;
}

// The source triangles of a run of samples (every triangle that holds one,
// once) and which serves each sample.
struct SourcePlan {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sources;  // (object, triangle)
    std::vector<std::uint32_t> ofSample;
};

SourcePlan planSources(const SurfaceScene& scene, const std::vector<SurfaceSample>& samples) {
    SourcePlan plan;
    // Per object and triangle its source index: flat arrays, as a frame's
    // hundreds of thousands of samples make hashing a visible cost.
    std::vector<std::vector<std::uint32_t>> index(scene.objectCount());
    plan.ofSample.reserve(samples.size());
    for (const SurfaceSample& s : samples) {
        auto& ofObject = index.at(s.object);
        if (ofObject.empty()) ofObject.assign(scene.object(s.object).triangles.size(), UINT32_MAX);
        std::uint32_t& source = ofObject.at(s.triangle);
        if (source == UINT32_MAX) {
            source = std::uint32_t(plan.sources.size());
            plan.sources.emplace_back(s.object, s.triangle);
        }
        plan.ofSample.push_back(source);
    }
    return plan;
}

}  // namespace

std::vector<ClosestPrimitive> closestPrimitivesReference(const SurfaceScene& scene,
                                                         const std::vector<SurfaceSample>& samples,
                                                         const DistanceQuery& query) {
    const SourcePlan plan = planSources(scene, samples);
    const double slackMm = cullSlackMm<double>(extentOf(scene));
    std::vector<SourceCandidates> sources;
    sources.reserve(plan.sources.size());
    for (const auto& [object, triangle] : plan.sources)
        sources.push_back(sourceCandidates(scene, object, triangle, query, slackMm));
    std::vector<ClosestPrimitive> answers(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const SurfaceSample& s = samples[k];
        const Found best = searchSample(scene, s, sources[plan.ofSample[k]], query, slackMm);
        if (best.object != SIZE_MAX)
            answers[k] = describe(scene, best.object, best.triangle, s.point);
    }
    return answers;
}

std::vector<ClosestPrimitive> closestPrimitivesAtReference(const SurfaceScene& scene,
                                                           const std::vector<Vec3>& points,
                                                           const DistanceQuery& query) {
    std::vector<ClosestPrimitive> answers(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
        Found best;
        best.distance2 = bandSquared(query);
        best = searchObjects(scene, points[k], kNoObject, best, query);
        if (best.object != SIZE_MAX)
            answers[k] = describe(scene, best.object, best.triangle, points[k]);
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

// The kernels' QueryParams (kernels/surface_distance.cl), member for
// member: the kernels read these bytes as they are, so the layout is
// asserted below for both of REAL's types.
template <class Real>
struct QueryParams {
    Real maxDistance2, maxDistance, slack;
    cl_uint objectCount;
    cl_int target;
    cl_uint capacity, sourceFirst, sourceCount, sampleFirst, sampleEnd;
    cl_uint padding = 0;
};

template <class Real>
constexpr bool queryParamsLaidOutAsTheKernels() {
    using P = QueryParams<Real>;
    constexpr std::size_t r = sizeof(Real), u = sizeof(cl_uint);
    return std::is_standard_layout_v<P> && std::is_trivially_copyable_v<P> &&
           offsetof(P, maxDistance2) == 0 && offsetof(P, maxDistance) == r &&
           offsetof(P, slack) == 2 * r && offsetof(P, objectCount) == 3 * r &&
           offsetof(P, target) == 3 * r + u && offsetof(P, capacity) == 3 * r + 2 * u &&
           offsetof(P, sourceFirst) == 3 * r + 3 * u && offsetof(P, sourceCount) == 3 * r + 4 * u &&
           offsetof(P, sampleFirst) == 3 * r + 5 * u && offsetof(P, sampleEnd) == 3 * r + 6 * u &&
           offsetof(P, padding) == 3 * r + 7 * u && sizeof(P) == 3 * r + 8 * u;
}
static_assert(queryParamsLaidOutAsTheKernels<cl_double>() && sizeof(QueryParams<cl_double>) == 56);
static_assert(queryParamsLaidOutAsTheKernels<cl_float>() && sizeof(QueryParams<cl_float>) == 44);

// What both kernels write per sample, on the device, and its download
// into answers (sample k of the launch is answers[order(k)]).
template <class Real, class Real4>
struct DeviceAnswers {
    ocl::DeviceBuffer<cl_uint> nearest;
    ocl::DeviceBuffer<Real> distance;
    ocl::DeviceBuffer<cl_uchar> feature;
    ocl::DeviceBuffer<Real4> closest;

    DeviceAnswers(ocl::Runtime& runtime, std::size_t count)
        : nearest(runtime, count, CL_MEM_WRITE_ONLY),
          distance(runtime, count, CL_MEM_WRITE_ONLY),
          feature(runtime, count, CL_MEM_WRITE_ONLY),
          closest(runtime, count, CL_MEM_WRITE_ONLY) {}

    /// The kernels' argument order: distance, nearest, feature, closest.
    std::array<const cl::Buffer*, 4> arguments() const {
        return {&distance.get(), &nearest.get(), &feature.get(), &closest.get()};
    }

    template <class Order>
    void collect(ocl::Runtime& runtime, const std::vector<std::size_t>& objectOfTriangle,
                 const std::vector<std::size_t>& firstTriangle, Order order,
                 std::vector<ClosestPrimitive>& answers) const {
        const std::vector<cl_uint> t = nearest.download(runtime);
        const std::vector<Real> d = distance.download(runtime);
        const std::vector<cl_uchar> f = feature.download(runtime);
        const std::vector<Real4> c = closest.download(runtime);
        for (std::size_t k = 0; k < t.size(); ++k) {
            if (t[k] == CL_UINT_MAX) continue;
            ClosestPrimitive& answer = answers[order(k)];
            answer.object = std::int32_t(objectOfTriangle[t[k]]);
            answer.triangle = std::uint32_t(t[k] - firstTriangle[objectOfTriangle[t[k]]]);
            answer.distanceMm = double(d[k]);
            answer.feature = TriangleFeature(f[k]);
            answer.point = {double(c[k].s[0]), double(c[k].s[1]), double(c[k].s[2])};
        }
    }
};

// The interface both precisions implement.
struct DeviceScene {
    virtual ~DeviceScene() = default;
    virtual std::vector<ClosestPrimitive> run(const std::vector<SurfaceSample>& samples,
                                              const DistanceQuery& query) = 0;
    virtual std::vector<ClosestPrimitive> runAt(const std::vector<Vec3>& points,
                                                const DistanceQuery& query) = 0;
    CullStats stats;  // of the last run
};

template <class Real, class Real4>
class DeviceSceneT final : public DeviceScene {
  public:
    DeviceSceneT(ocl::Runtime& runtime, const SurfaceScene& scene, double extentMm,
                 std::size_t sourcesPerLaunch)
        : runtime_(runtime),
          scene_(scene),
          slackMm_(cullSlackMm<Real>(extentMm)),
          sourcesPerLaunch_(sourcesPerLaunch) {
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
        std::vector<std::string> sources = surfaceProgramSources("surface_distance.cl");
        sources.insert(sources.end() - 1, "tangent_bound.cl");
        program_ = &runtime.program(sources, ocl::realOptions<Real>());
    }

    std::vector<ClosestPrimitive> run(const std::vector<SurfaceSample>& samples,
                                      const DistanceQuery& query) override {
        std::vector<ClosestPrimitive> answers(samples.size());
        stats = {};
        if (samples.empty()) return answers;
        const SourcePlan plan = planSources(scene_, samples);
        std::vector<Real4> corners;  // three per source triangle
        std::vector<cl_uint> sourceObject;
        corners.reserve(3 * plan.sources.size());
        for (const auto& [object, triangle] : plan.sources) {
            const TriangleSoup& soup = scene_.object(object);
            for (std::uint32_t v : soup.triangles[triangle])
                corners.push_back(SurfaceArrays<Real4>::real4(soup.points[v]));
            sourceObject.push_back(object);
        }
        // Samples sorted by source (a counting sort, stable): a chunk of
        // sources then serves one run of samples, and neighbouring
        // work-items share a list.
        const std::size_t sources = plan.sources.size(), count = samples.size();
        std::vector<std::size_t> sampleFirst(sources + 1, 0);
        for (std::uint32_t source : plan.ofSample) ++sampleFirst[source + 1];
        for (std::size_t s = 0; s < sources; ++s) sampleFirst[s + 1] += sampleFirst[s];
        std::vector<std::size_t> sorted(count);  // sorted position -> sample
        {
            std::vector<std::size_t> next(sampleFirst.begin(), sampleFirst.end() - 1);
            for (std::size_t k = 0; k < count; ++k) sorted[next[plan.ofSample[k]]++] = k;
        }
        std::vector<Real4> points(count);
        std::vector<cl_uint> sampleSource(count);
        for (std::size_t k = 0; k < count; ++k) {
            points[k] = SurfaceArrays<Real4>::real4(samples[sorted[k]].point);
            sampleSource[k] = plan.ofSample[sorted[k]];
        }

        const cl_uint capacity = cl_uint(kCandidateCapacity);
        const std::size_t chunk = std::min(sources, sourcesPerLaunch_);
        ocl::DeviceBuffer<Real4> dCorners(runtime_, corners);
        ocl::DeviceBuffer<cl_uint> dSourceObject(runtime_, sourceObject);
        ocl::DeviceBuffer<cl_uint> dCandidates(runtime_, chunk * capacity);
        ocl::DeviceBuffer<Real4> dBounds(runtime_, chunk * capacity);
        ocl::DeviceBuffer<cl_uint> dCandidateCount(runtime_, chunk);
        ocl::DeviceBuffer<cl_uint> dCentreNearest(runtime_, chunk);
        ocl::DeviceBuffer<Real4> dPoints(runtime_, points);
        ocl::DeviceBuffer<cl_uint> dSampleSource(runtime_, sampleSource);
        const DeviceAnswers<Real, Real4> written(runtime_, count);
        try {
            cl::Kernel cull(*program_, "source_candidates");
            cl::Kernel kernel(*program_, "closest_primitive");
            // The leading arguments both kernels share, then each one's own;
            // the query and the chunk follow, set per chunk.
            const auto setShared = [&](cl::Kernel& k) {
                cl_uint a = 0;
                k.setArg(a++, dCorners.get());
                k.setArg(a++, dSourceObject.get());
                a = surface_.setArgs(k, a);
                k.setArg(a++, objectRoot_.get());
                k.setArg(a++, dCandidates.get());
                k.setArg(a++, dBounds.get());
                k.setArg(a++, dCandidateCount.get());
                k.setArg(a++, dCentreNearest.get());
                return a;
            };
            const cl_uint cullQuery = setShared(cull);
            cl_uint sampleQuery = setShared(kernel);
            for (const cl::Buffer* buffer :
                 {&normals_.get(), &closed_.get(), &dPoints.get(), &dSampleSource.get()})
                kernel.setArg(sampleQuery++, *buffer);
            for (const cl::Buffer* buffer : written.arguments())
                kernel.setArg(sampleQuery++, *buffer);
            QueryParams<Real> params{};
            params.maxDistance2 = Real(bandSquared(query));
            params.maxDistance = Real(query.maxDistanceMm);
            params.slack = Real(slackMm_);
            params.objectCount = cl_uint(roots_.size());
            params.target = cl_int(query.target);
            params.capacity = capacity;
            for (std::size_t first = 0; first < sources; first += chunk) {
                const std::size_t last = std::min(sources, first + chunk);
                params.sourceFirst = cl_uint(first);
                params.sourceCount = cl_uint(last - first);
                params.sampleFirst = cl_uint(sampleFirst[first]);
                params.sampleEnd = cl_uint(sampleFirst[last]);
                // Pass 1: per source triangle, the candidates of all its samples.
                cull.setArg(cullQuery, params);
                runtime_.queue().enqueueNDRangeKernel(
                    cull, cl::NullRange, cl::NDRange(ocl::roundUp(last - first, ocl::kGroupSize1D)),
                    cl::NDRange(ocl::kGroupSize1D));
                // Pass 2: per sample of these sources (every source holds
                // one), their candidates or the hierarchies.
                kernel.setArg(sampleQuery, params);
                runtime_.queue().enqueueNDRangeKernel(
                    kernel, cl::NullRange,
                    cl::NDRange(
                        ocl::roundUp(sampleFirst[last] - sampleFirst[first], ocl::kGroupSize1D)),
                    cl::NDRange(ocl::kGroupSize1D));
                // Before the next chunk overwrites the lists.
                countCandidates(dCandidateCount, last - first, capacity);
            }
        } catch (const cl::Error& e) {
            throw ocl::toClError(e, "surface_distance.cl");
        }
        written.collect(
            runtime_, objectOfTriangle_, firstTriangle_, [&](std::size_t k) { return sorted[k]; },
            answers);
        return answers;
    }

    std::vector<ClosestPrimitive> runAt(const std::vector<Vec3>& queryPoints,
                                        const DistanceQuery& query) override {
        const std::size_t count = queryPoints.size();
        std::vector<ClosestPrimitive> answers(count);
        if (count == 0) return answers;
        std::vector<Real4> points(count);
        for (std::size_t k = 0; k < count; ++k)
            points[k] = SurfaceArrays<Real4>::real4(queryPoints[k]);
        ocl::DeviceBuffer<Real4> dPoints(runtime_, points);
        const DeviceAnswers<Real, Real4> written(runtime_, count);
        try {
            cl::Kernel kernel(*program_, "closest_primitive_at");
            cl_uint a = surface_.setArgs(kernel, 0);
            for (const cl::Buffer* buffer :
                 {&objectRoot_.get(), &normals_.get(), &closed_.get(), &dPoints.get()})
                kernel.setArg(a++, *buffer);
            for (const cl::Buffer* buffer : written.arguments()) kernel.setArg(a++, *buffer);
            QueryParams<Real> params{};
            params.maxDistance2 = Real(bandSquared(query));
            params.maxDistance = Real(query.maxDistanceMm);
            params.objectCount = cl_uint(roots_.size());
            params.target = cl_int(query.target);
            // Launches of a bounded size, so one launch never holds a
            // device (and a desktop's display) for long.
            for (std::size_t first = 0; first < count; first += kPointsPerLaunch) {
                const std::size_t last = std::min(count, first + kPointsPerLaunch);
                params.sampleFirst = cl_uint(first);
                params.sampleEnd = cl_uint(last);
                kernel.setArg(a, params);
                runtime_.queue().enqueueNDRangeKernel(
                    kernel, cl::NullRange,
                    cl::NDRange(ocl::roundUp(last - first, ocl::kGroupSize1D)),
                    cl::NDRange(ocl::kGroupSize1D));
            }
        } catch (const cl::Error& e) {
            throw ocl::toClError(e, "surface_distance.cl");
        }
        written.collect(
            runtime_, objectOfTriangle_, firstTriangle_, [](std::size_t k) { return k; }, answers);
        return answers;
    }

  private:
    // Adds a chunk's list lengths to stats (a small read: one count per
    // source triangle).
    void countCandidates(const ocl::DeviceBuffer<cl_uint>& counts, std::size_t sources,
                         cl_uint capacity) {
        std::vector<cl_uint> count(sources);
        runtime_.queue().enqueueReadBuffer(counts.get(), CL_TRUE, 0, sizeof(cl_uint) * sources,
                                           count.data());
        for (const cl_uint n : count) {
            ++stats.sources;
            if (n > capacity)
                ++stats.overflowing;
            else
                stats.candidates += n;
        }
    }

    ocl::Runtime& runtime_;
    const SurfaceScene& scene_;
    const cl::Program* program_ = nullptr;
    double slackMm_;  // the culling's rounding allowance (cullSlackMm)
    std::size_t sourcesPerLaunch_;
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

ClosestPrimitiveKernel::ClosestPrimitiveKernel(ocl::Runtime& runtime, const SurfaceScene& scene,
                                               std::size_t sourcesPerLaunch)
    : impl_(std::make_unique<Impl>()) {
    if (sourcesPerLaunch == 0) sourcesPerLaunch = kSourcesPerLaunch;
    impl_->doublePrecision = runtime.device().doublePrecision;
    impl_->extentMm = extentOf(scene);
    impl_->device = ocl::withRealTypes(
        impl_->doublePrecision, [&](auto real, auto real4) -> std::unique_ptr<DeviceScene> {
            return std::make_unique<DeviceSceneT<decltype(real), decltype(real4)>>(
                runtime, scene, impl_->extentMm, sourcesPerLaunch);
        });
}

ClosestPrimitiveKernel::~ClosestPrimitiveKernel() = default;

std::vector<ClosestPrimitive> ClosestPrimitiveKernel::run(const std::vector<SurfaceSample>& samples,
                                                          const DistanceQuery& query) {
    return impl_->device->run(samples, query);
}

std::vector<ClosestPrimitive> ClosestPrimitiveKernel::runAt(const std::vector<Vec3>& points,
                                                            const DistanceQuery& query) {
    return impl_->device->runAt(points, query);
}

CullStats ClosestPrimitiveKernel::lastCullStats() const {
    return impl_->device->stats;
}

double ClosestPrimitiveKernel::toleranceMm() const {
    return (impl_->doublePrecision ? 1e-12 : 1e-6) * impl_->extentMm;
}

}  // namespace dfrecon
