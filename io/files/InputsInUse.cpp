#include "io/files/InputsInUse.hpp"

#include <algorithm>
#include <exception>
#include <mutex>

namespace dfrecon {

namespace {

struct State {
    std::mutex mutex;
    std::vector<std::string> reading;  // nested reads, innermost last
    std::vector<std::string> inputs;
    std::string failed;  // the innermost read that ended in an exception
    std::string last;    // the read begun most recently
};

State& state() {
    static State s;
    return s;
}

}  // namespace

ReadingInput::ReadingInput(const std::string& path) : exceptions_(std::uncaught_exceptions()) {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    s.reading.push_back(path);
    s.last = path;
    s.failed.clear();
    if (std::find(s.inputs.begin(), s.inputs.end(), path) == s.inputs.end())
        s.inputs.push_back(path);
}

ReadingInput::~ReadingInput() {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    // Unwinding: the exception that ends this read came from inside it
    // (an inner read that failed has already said so).
    if (std::uncaught_exceptions() > exceptions_ && s.failed.empty()) s.failed = s.reading.back();
    s.reading.pop_back();
}

InputsInUse inputsInUse() {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    InputsInUse in;
    in.reading = !s.failed.empty() ? s.failed : s.reading.empty() ? "" : s.reading.back();
    in.inputs = s.inputs;
    return in;
}

std::string lastInput() {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    return s.last;
}

}  // namespace dfrecon
