#include "geometry/PolygonXor.hpp"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <pthread.h>

#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <map>
#include <string>

#include "geometry/ContourValidation.hpp"

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
// Each segment carries its own id; where segments overlap, the arrangement
// edge carries every id that covers it, so its multiplicity is known.
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, std::uint32_t>;
// A face's data: 1 inside, 0 outside, -1 not yet known.
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;

// CGAL's sweep and face scans recurse (48 000 crossing points overflowed
// the 8 MB main stack). The work runs on a thread of its own with this much
// stack: with the faces bounded by xorRegions' work limit, far more than it
// needs.
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

// Faces separated by an edge of odd multiplicity differ in parity; the
// unbounded face is outside. Even edges are gone by now, so every edge
// flips it. Breadth first, no recursion.
void markInside(Arrangement& arrangement) {
    for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f) f->set_data(-1);
    std::deque<Arrangement::Face_handle> pending{arrangement.unbounded_face()};
    pending.front()->set_data(0);
    auto visit = [&](Arrangement::Face_handle face, Arrangement::Ccb_halfedge_circulator first) {
        auto h = first;
        do {
            const Arrangement::Face_handle other = h->twin()->face();
            if (other->data() < 0) {
                other->set_data(1 - face->data());
                pending.push_back(other);
            }
        } while (++h != first);
    };
    while (!pending.empty()) {
        const Arrangement::Face_handle face = pending.front();
        pending.pop_front();
        for (auto c = face->outer_ccbs_begin(); c != face->outer_ccbs_end(); ++c) visit(face, *c);
        for (auto c = face->inner_ccbs_begin(); c != face->inner_ccbs_end(); ++c) visit(face, *c);
    }
}

// The loops of one boundary cycle: a cycle that passes a vertex twice (a
// hole touching its outer boundary, two lobes meeting at a point) is cut
// there into simple loops, each keeping the direction it ran in.
void appendLoops(Arrangement::Ccb_halfedge_const_circulator first, std::vector<Polygon>& out) {
    std::vector<Arrangement::Vertex_const_handle> path;
    std::map<Arrangement::Vertex_const_handle, std::size_t> onPath;
    auto emit = [&](std::size_t from) {
        Polygon loop;
        for (std::size_t i = from; i < path.size(); ++i) {
            const Point2 p{CGAL::to_double(path[i]->point().x()),
                           CGAL::to_double(path[i]->point().y())};
            // Crossing points rounded onto a neighbour would be zero-length
            // segments.
            if (loop.empty() || loop.back() != p) loop.push_back(p);
        }
        while (loop.size() > 1 && loop.back() == loop.front()) loop.pop_back();
        if (loop.size() >= 3 && !allCollinear(loop)) out.push_back(std::move(loop));
        for (std::size_t i = from; i < path.size(); ++i) onPath.erase(path[i]);
        path.resize(from);
    };
    auto h = first;
    do {
        const Arrangement::Vertex_const_handle v = h->source();
        if (const auto seen = onPath.find(v); seen != onPath.end()) {
            const std::size_t from = seen->second;
            emit(from);
        }
        onPath[v] = path.size();
        path.push_back(v);
    } while (++h != first);
    emit(0);
}

}  // namespace

std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours, std::size_t maxWork,
                                std::size_t* work) {
    // The arrangement has about one face per crossing point plus one per
    // contour: their sum bounds its memory, time and recursion.
    const std::size_t budget = maxWork > contours.size() ? maxWork - contours.size() : 0;
    const std::size_t crossings =
        contours.size() > maxWork
            ? SIZE_MAX
            : countContourContacts(contours, budget, kDefaultPairBudget, ContactsCounted::All);
    if (crossings > budget)
        throw TooManyCrossings(std::to_string(contours.size()) + " contours meeting in " +
                               (crossings == SIZE_MAX
                                    ? std::string("too many places to count")
                                    : "more than " + std::to_string(budget) + " places") +
                               ": more than the exclusive or combines (" + std::to_string(maxWork) +
                               " contours and crossing points together)");
    if (work) *work = contours.size() + crossings;
    std::vector<Polygon> out;
    runWithStack(kCgalStackBytes, [&] {
        std::vector<Traits::Curve_2> segments;
        for (const Polygon& contour : contours)
            for (std::size_t i = 0; i < contour.size(); ++i) {
                const Point2 a = contour[i], b = contour[(i + 1) % contour.size()];
                if (a == b) continue;
                segments.emplace_back(
                    Kernel::Segment_2(Kernel::Point_2(a.x, a.y), Kernel::Point_2(b.x, b.y)),
                    std::uint32_t(segments.size()));
            }
        Arrangement arrangement;
        // The aggregated sweep: one pass over every segment, not one
        // insertion (and point location) per segment.
        CGAL::insert(arrangement, segments.begin(), segments.end());
        // A piece covered an even number of times is crossed an even number
        // of times by any ray through it: it bounds nothing.
        std::vector<Arrangement::Halfedge_handle> even;
        for (auto e = arrangement.edges_begin(); e != arrangement.edges_end(); ++e)
            if (e->curve().data().size() % 2 == 0) even.push_back(e);
        for (Arrangement::Halfedge_handle e : even) arrangement.remove_edge(e);
        markInside(arrangement);
        // A face lies left of its boundary's halfedges: outer cycles run
        // counter-clockwise, the cycles of its holes clockwise.
        for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f) {
            if (f->data() != 1) continue;
            for (auto c = f->outer_ccbs_begin(); c != f->outer_ccbs_end(); ++c)
                appendLoops(*c, out);
            for (auto c = f->inner_ccbs_begin(); c != f->inner_ccbs_end(); ++c)
                appendLoops(*c, out);
        }
    });
    return out;
}

}  // namespace dfrecon
