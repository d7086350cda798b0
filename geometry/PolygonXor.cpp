#include "geometry/PolygonXor.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>

#include <pthread.h>

#include <cstdint>
#include <exception>
#include <functional>
#include <string>

#include "geometry/ContourValidation.hpp"

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;

CgalPolygon toCgal(const Polygon& polygon) {
    CgalPolygon out;
    for (const Point2& p : polygon) out.push_back(Kernel::Point_2(p.x, p.y));
    if (out.is_clockwise_oriented()) out.reverse_orientation();
    return out;
}

Polygon fromCgal(const CgalPolygon& polygon, bool clockwise) {
    Polygon out;
    for (auto it = polygon.vertices_begin(); it != polygon.vertices_end(); ++it)
        out.push_back({CGAL::to_double(it->x()), CGAL::to_double(it->y())});
    if ((signedArea(out) < 0) != clockwise) std::reverse(out.begin(), out.end());
    return out;
}

// CGAL's arrangement is scanned recursively, one call per face it reaches
// (48 000 crossing points overflowed the 8 MB main stack). The Boolean
// operation runs on a thread of its own with this much stack: with the
// faces bounded by xorRegions' work limit, far more than it needs.
constexpr std::size_t kCgalStackBytes = std::size_t(256) << 20;

// Runs `work` to its end on a thread with `stackBytes` of stack, passing on
// what it throws.
void runWithStack(std::size_t stackBytes, const std::function<void()>& work) {
    struct Job {
        const std::function<void()>* work;
        std::exception_ptr error;
    } job{&work, nullptr};
    auto body = [](void* argument) -> void* {
        Job& j = *static_cast<Job*>(argument);
        try {
            (*j.work)();
        } catch (...) {
            j.error = std::current_exception();
        }
        return nullptr;
    };
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, stackBytes);
    pthread_t thread;
    const int status = pthread_create(&thread, &attributes, body, &job);
    pthread_attr_destroy(&attributes);
    if (status != 0) throw std::bad_alloc();  // no memory for the stack
    pthread_join(thread, nullptr);
    if (job.error) std::rethrow_exception(job.error);
}

}  // namespace

std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours, std::size_t maxWork,
                                std::size_t* work) {
    // The arrangement has about one face per crossing point plus one per
    // contour: their sum bounds its memory, time and recursion.
    const std::size_t budget = maxWork > contours.size() ? maxWork - contours.size() : 0;
    const std::size_t crossings =
        contours.size() > maxWork ? SIZE_MAX : countContourContacts(contours, budget);
    if (crossings > budget)
        throw TooManyCrossings(std::to_string(contours.size()) + " contours meeting in " +
                               (crossings == SIZE_MAX
                                    ? std::string("too many places to count")
                                    : "more than " + std::to_string(budget) + " places") +
                               ": more than the exclusive or combines (" + std::to_string(maxWork) +
                               " contours and crossing points together)");
    if (work) *work = contours.size() + crossings;
    std::vector<PolygonWithHoles> pieces;
    runWithStack(kCgalStackBytes, [&] {
        std::vector<CgalPolygon> polygons;
        for (const Polygon& contour : contours) polygons.push_back(toCgal(contour));
        // The range form merges divide-and-conquer; one polygon at a time
        // would rebuild the growing arrangement every step (quadratic).
        CGAL::Polygon_set_2<Kernel> region;
        region.symmetric_difference(polygons.begin(), polygons.end());
        region.polygons_with_holes(std::back_inserter(pieces));
    });
    std::vector<Polygon> out;
    for (const PolygonWithHoles& piece : pieces) {
        out.push_back(fromCgal(piece.outer_boundary(), false));
        for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole)
            out.push_back(fromCgal(*hole, true));
    }
    return out;
}

}  // namespace dfrecon
