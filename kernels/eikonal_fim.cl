// The fast iterative method (Jeong & Whitaker 2008; on triangle meshes Fu,
// Kirby & Whitaker 2011) over the stencils of segment/UpdateStencils, with
// closest-source labels. Needs eikonal_update.cl first. The host loop and
// the C++ reference are segment/EikonalFim.cpp; every phase reads only
// values committed by an earlier kernel, so the result does not depend on
// the order work-items run in and equals the reference's.
//
// One iteration over the active list:
//   fim_update       each active vertex solves from its stencils (slot values)
//   fim_commit       the slot values become the vertex's time and label
//   fim_expand       a vertex that moved by more than the tolerance stays
//                    active; one that settled checks the vertices it may
//                    update (claimed once per iteration) and activates
//                    those it would improve by more than the tolerance
//   fim_commit_next  the activated vertices take their new times; the
//                    next list becomes the active one

// The best time at v from all its stencils with the current times, and the
// label that comes with it. Across a face when both corners are reached
// and carry the same label (as in fast marching).
inline REAL fim_solve(int v, __global const int* stencil_first,
                      __global const int2* stencil_corners, __global const REAL4* stencil_shape,
                      __global const REAL* slowness, __global const REAL* time,
                      __global const int* label, int* best_label) {
    REAL best = INFINITY;
    int best_l = -1;
    const REAL p = slowness[v];
    for (int k = stencil_first[v]; k < stencil_first[v + 1]; ++k) {
        const int2 ab = stencil_corners[k];
        const REAL4 shape = stencil_shape[k];
        const REAL ta = time[ab.x], tb = time[ab.y];
        const int la = label[ab.x], lb = label[ab.y];
        int via;
        REAL weight;
        const REAL t =
            eikonal_triangle_update(ta, tb, shape.x, shape.y, shape.z, p,
                                    ta < INFINITY && tb < INFINITY && la == lb, &via, &weight);
        if (t < best) {
            best = t;
            best_l = eikonal_upwind_label(via, la, lb);
        }
    }
    *best_label = best_l;
    return best;
}

__kernel void fim_update(__global const int* list, uint count, __global const int* stencil_first,
                         __global const int2* stencil_corners, __global const REAL4* stencil_shape,
                         __global const REAL* slowness, __global const REAL* time,
                         __global const int* label, REAL tolerance, __global REAL* slot_time,
                         __global int* slot_label, __global uchar* slot_settled) {
    const uint i = get_global_id(0);
    if (i >= count) return;
    const int v = list[i];
    int l;
    const REAL t =
        fim_solve(v, stencil_first, stencil_corners, stencil_shape, slowness, time, label, &l);
    const REAL old = time[v];
    if (t < old) {
        slot_time[i] = t;
        slot_label[i] = l;
        slot_settled[i] = old - t <= tolerance;
    } else {
        slot_time[i] = old;
        slot_label[i] = label[v];
        slot_settled[i] = 1;
    }
}

__kernel void fim_commit(__global const int* list, uint count, __global const REAL* slot_time,
                         __global const int* slot_label, __global REAL* time, __global int* label) {
    const uint i = get_global_id(0);
    if (i >= count) return;
    time[list[i]] = slot_time[i];
    label[list[i]] = slot_label[i];
}

// member[v] == iteration: v is in this iteration's list (never a candidate);
// claimed[v] == iteration + 1: some work-item already checked v this time.
__kernel void fim_expand(__global const int* list, uint count, __global const uchar* slot_settled,
                         __global const int* dependent_first, __global const int* dependents,
                         __global const int* stencil_first, __global const int2* stencil_corners,
                         __global const REAL4* stencil_shape, __global const REAL* slowness,
                         __global const REAL* time, __global const int* label, REAL tolerance,
                         __global const uint* member, __global volatile uint* claimed,
                         uint iteration, __global int* next_list, __global REAL* next_time,
                         __global int* next_label, __global volatile uint* next_count) {
    const uint i = get_global_id(0);
    if (i >= count) return;
    const int v = list[i];
    if (!slot_settled[i]) {
        const uint slot = atomic_inc(next_count);
        next_list[slot] = v;
        next_time[slot] = time[v];
        next_label[slot] = label[v];
        return;
    }
    for (int k = dependent_first[v]; k < dependent_first[v + 1]; ++k) {
        const int n = dependents[k];
        if (member[n] == iteration) continue;
        const uint seen = claimed[n];
        if (seen == iteration + 1 || atomic_cmpxchg(&claimed[n], seen, iteration + 1) != seen)
            continue;
        int l;
        const REAL t =
            fim_solve(n, stencil_first, stencil_corners, stencil_shape, slowness, time, label, &l);
        if (t < time[n] - tolerance) {
            const uint slot = atomic_inc(next_count);
            next_list[slot] = n;
            next_time[slot] = t;
            next_label[slot] = l;
        }
    }
}

__kernel void fim_commit_next(__global const int* next_list, uint count,
                              __global const REAL* next_time, __global const int* next_label,
                              uint next_iteration, __global REAL* time, __global int* label,
                              __global uint* member) {
    const uint i = get_global_id(0);
    if (i >= count) return;
    const int v = next_list[i];
    time[v] = next_time[i];
    label[v] = next_label[i];
    member[v] = next_iteration;
}
