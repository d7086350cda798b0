#include "segment/EikonalFim.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "cl/ClError.hpp"
#include "cl/DeviceBuffer.hpp"
#include "cl/Precision.hpp"
#include "segment/LocalUpdate.hpp"

namespace dfrecon {

namespace {

/// The absolute settling tolerance: options.tolerance of a typical edge's
/// crossing time.
double absoluteTolerance(const UpdateStencils& stencils, const std::vector<double>& slowness,
                         const FimOptions& options) {
    const double meanSlowness =
        slowness.empty()
            ? 1.0
            : std::accumulate(slowness.begin(), slowness.end(), 0.0) / double(slowness.size());
    return options.tolerance * stencils.meanEdgeLength() * meanSlowness;
}

int iterationLimit(const UpdateStencils& stencils, const FimOptions& options) {
    return options.maxIterations > 0 ? options.maxIterations : 4 * stencils.vertexCount() + 100;
}

/// The sources' times and labels (a vertex listed twice keeps the smaller
/// time, the first on ties, as in FastMarching) and the first active list.
GeodesicField startField(int vertexCount, const std::vector<GeodesicSource>& sources,
                         std::vector<int>& active) {
    GeodesicField field{std::size_t(vertexCount)};
    active.clear();
    for (const GeodesicSource& s : sources) {
        if (s.vertex < 0 || s.vertex >= vertexCount)
            throw std::invalid_argument("source vertex " + std::to_string(s.vertex) +
                                        " out of range");
        const std::size_t v = std::size_t(s.vertex);
        if (field.time[v] == kUnreached) active.push_back(s.vertex);
        if (s.time < field.time[v]) {
            field.time[v] = s.time;
            field.label[v] = s.label;
        }
    }
    return field;
}

/// fim_solve of kernels/eikonal_fim.cl.
double solveAt(int v, const UpdateStencils& stencils, const std::vector<double>& slowness,
               const GeodesicField& field, int& bestLabel) {
    double best = kUnreached;
    bestLabel = -1;
    const double p = slowness[std::size_t(v)];
    for (int k = stencils.first()[std::size_t(v)]; k < stencils.first()[std::size_t(v) + 1]; ++k) {
        const UpdateStencil& s = stencils.stencils()[std::size_t(k)];
        const double ta = field.time[std::size_t(s.a)], tb = field.time[std::size_t(s.b)];
        const int la = field.label[std::size_t(s.a)], lb = field.label[std::size_t(s.b)];
        const TriangleUpdate u = triangleUpdate(ta, tb, {s.lengthA, s.lengthB, s.cosAngle}, p,
                                                ta < kUnreached && tb < kUnreached && la == lb);
        if (u.time < best) {
            best = u.time;
            bestLabel = upwindLabel(u, la, lb);
        }
    }
    return best;
}

}  // namespace

GeodesicField eikonalFimReference(const UpdateStencils& stencils,
                                  const std::vector<GeodesicSource>& sources,
                                  const std::vector<double>& speed, const FimOptions& options,
                                  FimStats* stats) {
    const int n = stencils.vertexCount();
    const std::vector<double> slowness = slownessFromSpeed(speed, n);
    const double tolerance = absoluteTolerance(stencils, slowness, options);
    std::vector<int> list;
    GeodesicField field = startField(n, sources, list);
    std::vector<unsigned> member(std::size_t(n), 0), claimed(std::size_t(n), 0);
    for (int v : list) member[std::size_t(v)] = 1;
    struct Slot {
        double time;
        int label;
        bool settled;
    };
    std::vector<Slot> slots;
    std::vector<int> nextList;
    std::vector<double> nextTime;
    std::vector<int> nextLabel;
    FimStats local;
    const int limit = iterationLimit(stencils, options);
    unsigned iteration = 1;
    for (; !list.empty() && int(iteration) <= limit; ++iteration) {
        local.vertexUpdates += list.size();
        slots.resize(list.size());
        for (std::size_t i = 0; i < list.size(); ++i) {  // fim_update
            const std::size_t v = std::size_t(list[i]);
            int label = -1;
            const double t = solveAt(list[i], stencils, slowness, field, label);
            const double old = field.time[v];
            slots[i] =
                t < old ? Slot{t, label, old - t <= tolerance} : Slot{old, field.label[v], true};
        }
        for (std::size_t i = 0; i < list.size(); ++i) {  // fim_commit
            field.time[std::size_t(list[i])] = slots[i].time;
            field.label[std::size_t(list[i])] = slots[i].label;
        }
        nextList.clear();
        nextTime.clear();
        nextLabel.clear();
        for (std::size_t i = 0; i < list.size(); ++i) {  // fim_expand
            const int v = list[i];
            if (!slots[i].settled) {
                nextList.push_back(v);
                nextTime.push_back(field.time[std::size_t(v)]);
                nextLabel.push_back(field.label[std::size_t(v)]);
                continue;
            }
            for (int k = stencils.dependentFirst()[std::size_t(v)];
                 k < stencils.dependentFirst()[std::size_t(v) + 1]; ++k) {
                const int candidate = stencils.dependents()[std::size_t(k)];
                const std::size_t c = std::size_t(candidate);
                if (member[c] == iteration || claimed[c] == iteration + 1) continue;
                claimed[c] = iteration + 1;
                int label = -1;
                const double t = solveAt(candidate, stencils, slowness, field, label);
                if (t < field.time[c] - tolerance) {
                    nextList.push_back(candidate);
                    nextTime.push_back(t);
                    nextLabel.push_back(label);
                }
            }
        }
        for (std::size_t i = 0; i < nextList.size(); ++i) {  // fim_commit_next
            const std::size_t v = std::size_t(nextList[i]);
            field.time[v] = nextTime[i];
            field.label[v] = nextLabel[i];
            member[v] = iteration + 1;
        }
        list.swap(nextList);
    }
    local.iterations = int(iteration) - 1;
    local.converged = list.empty();
    if (stats) *stats = local;
    return field;
}

// ---------------------------------------------------------------------------

class EikonalFim::Device {
  public:
    virtual ~Device() = default;
    virtual GeodesicField solve(const std::vector<GeodesicSource>& sources, FimStats* stats) = 0;
};

namespace {

template <class Real, class Real4>
class FimDevice final : public EikonalFim::Device {
  public:
    FimDevice(ocl::Runtime& runtime, const UpdateStencils& stencils,
              const std::vector<double>& speed, const FimOptions& options)
        : runtime_(runtime),
          n_(std::size_t(stencils.vertexCount())),
          limit_(iterationLimit(stencils, options)) {
        const std::vector<double> slowness = slownessFromSpeed(speed, stencils.vertexCount());
        tolerance_ = Real(absoluteTolerance(stencils, slowness, options));
        std::vector<cl_int2> corners;
        std::vector<Real4> shapes;
        corners.reserve(stencils.stencils().size());
        shapes.reserve(stencils.stencils().size());
        for (const UpdateStencil& s : stencils.stencils()) {
            corners.push_back({{s.a, s.b}});
            Real4 shape{};
            shape.s[0] = Real(s.lengthA);
            shape.s[1] = Real(s.lengthB);
            shape.s[2] = Real(s.cosAngle);
            shapes.push_back(shape);
        }
        stencilFirst_ = ocl::DeviceBuffer<cl_int>(runtime, stencils.first());
        corners_ = ocl::DeviceBuffer<cl_int2>(runtime, corners);
        shapes_ = ocl::DeviceBuffer<Real4>(runtime, shapes);
        dependentFirst_ = ocl::DeviceBuffer<cl_int>(runtime, stencils.dependentFirst());
        dependents_ = ocl::DeviceBuffer<cl_int>(runtime, stencils.dependents());
        slowness_ =
            ocl::DeviceBuffer<Real>(runtime, std::vector<Real>(slowness.begin(), slowness.end()));
        time_ = ocl::DeviceBuffer<Real>(runtime, n_);
        label_ = ocl::DeviceBuffer<cl_int>(runtime, n_);
        member_ = ocl::DeviceBuffer<cl_uint>(runtime, n_);
        claimed_ = ocl::DeviceBuffer<cl_uint>(runtime, n_);
        for (auto* list : {&list_, &nextList_}) *list = ocl::DeviceBuffer<cl_int>(runtime, n_);
        slotTime_ = ocl::DeviceBuffer<Real>(runtime, n_);
        nextTime_ = ocl::DeviceBuffer<Real>(runtime, n_);
        slotLabel_ = ocl::DeviceBuffer<cl_int>(runtime, n_);
        nextLabel_ = ocl::DeviceBuffer<cl_int>(runtime, n_);
        slotSettled_ = ocl::DeviceBuffer<cl_uchar>(runtime, n_);
        nextCount_ = ocl::DeviceBuffer<cl_uint>(runtime, 1);
        const cl::Program& program = runtime.program(
            {"real.cl", "eikonal_update.cl", "eikonal_fim.cl"}, ocl::realOptions<Real>());
        try {
            update_ = cl::Kernel(program, "fim_update");
            commit_ = cl::Kernel(program, "fim_commit");
            expand_ = cl::Kernel(program, "fim_expand");
            commitNext_ = cl::Kernel(program, "fim_commit_next");
        } catch (const cl::Error& e) {
            throw ocl::toClError(e, "eikonal_fim.cl");
        }
    }

    GeodesicField solve(const std::vector<GeodesicSource>& sources, FimStats* stats) override {
        std::vector<int> active;
        GeodesicField field = startField(int(n_), sources, active);
        FimStats local;
        local.doublePrecision = sizeof(Real) == 8;
        try {
            time_.upload(runtime_, std::vector<Real>(field.time.begin(), field.time.end()));
            label_.upload(runtime_, field.label);
            std::vector<cl_uint> member(n_, 0);
            for (int v : active) member[std::size_t(v)] = 1;
            member_.upload(runtime_, member);
            claimed_.upload(runtime_, std::vector<cl_uint>(n_, 0));
            if (!active.empty())
                runtime_.queue().enqueueWriteBuffer(list_.get(), CL_TRUE, 0,
                                                    sizeof(cl_int) * active.size(), active.data());
            cl_uint count = cl_uint(active.size());
            cl_uint iteration = 1;
            cl::CommandQueue& queue = runtime_.queue();
            for (; count > 0 && int(iteration) <= limit_; ++iteration) {
                local.vertexUpdates += count;
                const cl::NDRange global(ocl::roundUp(count, ocl::kGroupSize1D));
                const cl::NDRange group(ocl::kGroupSize1D);
                setArgs(update_, list_.get(), count, stencilFirst_.get(), corners_.get(),
                        shapes_.get(), slowness_.get(), time_.get(), label_.get(), tolerance_,
                        slotTime_.get(), slotLabel_.get(), slotSettled_.get());
                queue.enqueueNDRangeKernel(update_, cl::NullRange, global, group);
                setArgs(commit_, list_.get(), count, slotTime_.get(), slotLabel_.get(), time_.get(),
                        label_.get());
                queue.enqueueNDRangeKernel(commit_, cl::NullRange, global, group);
                queue.enqueueFillBuffer(nextCount_.get(), cl_uint(0), 0, sizeof(cl_uint));
                setArgs(expand_, list_.get(), count, slotSettled_.get(), dependentFirst_.get(),
                        dependents_.get(), stencilFirst_.get(), corners_.get(), shapes_.get(),
                        slowness_.get(), time_.get(), label_.get(), tolerance_, member_.get(),
                        claimed_.get(), iteration, nextList_.get(), nextTime_.get(),
                        nextLabel_.get(), nextCount_.get());
                queue.enqueueNDRangeKernel(expand_, cl::NullRange, global, group);
                queue.enqueueReadBuffer(nextCount_.get(), CL_TRUE, 0, sizeof(cl_uint), &count);
                if (count > 0) {
                    setArgs(commitNext_, nextList_.get(), count, nextTime_.get(), nextLabel_.get(),
                            cl_uint(iteration + 1), time_.get(), label_.get(), member_.get());
                    queue.enqueueNDRangeKernel(commitNext_, cl::NullRange,
                                               cl::NDRange(ocl::roundUp(count, ocl::kGroupSize1D)),
                                               cl::NDRange(ocl::kGroupSize1D));
                }
                std::swap(list_, nextList_);
            }
            local.iterations = int(iteration) - 1;
            local.converged = count == 0;
            const std::vector<Real> time = time_.download(runtime_);
            field.time.assign(time.begin(), time.end());
            field.label = label_.download(runtime_);
        } catch (const cl::Error& e) {
            throw ocl::toClError(e, "eikonal_fim.cl");
        }
        // Float devices carry float's infinity; keep the one callers test for.
        for (double& t : field.time)
            if (std::isinf(t)) t = kUnreached;
        if (stats) *stats = local;
        return field;
    }

  private:
    template <class... Args>
    static void setArgs(cl::Kernel& kernel, const Args&... args) {
        cl_uint index = 0;
        (kernel.setArg(index++, args), ...);
    }

    ocl::Runtime& runtime_;
    std::size_t n_;
    int limit_;
    Real tolerance_ = 0;
    ocl::DeviceBuffer<cl_int> stencilFirst_, dependentFirst_, dependents_, label_, list_, nextList_,
        slotLabel_, nextLabel_;
    ocl::DeviceBuffer<cl_int2> corners_;
    ocl::DeviceBuffer<Real4> shapes_;
    ocl::DeviceBuffer<Real> slowness_, time_, slotTime_, nextTime_;
    ocl::DeviceBuffer<cl_uint> member_, claimed_, nextCount_;
    ocl::DeviceBuffer<cl_uchar> slotSettled_;
    cl::Kernel update_, commit_, expand_, commitNext_;
};

}  // namespace

EikonalFim::EikonalFim(ocl::Runtime& runtime, const UpdateStencils& stencils,
                       const std::vector<double>& speed, const FimOptions& options) {
    device_ = ocl::withRealTypes(
        runtime.device().doublePrecision, [&](auto real, auto real4) -> std::unique_ptr<Device> {
            return std::make_unique<FimDevice<decltype(real), decltype(real4)>>(runtime, stencils,
                                                                                speed, options);
        });
}

EikonalFim::~EikonalFim() = default;

GeodesicField EikonalFim::solve(const std::vector<GeodesicSource>& sources, FimStats* stats) {
    return device_->solve(sources, stats);
}

}  // namespace dfrecon
