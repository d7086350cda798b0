// The inputs a run has read, and the one whose read failed, for messages
// about failures that carry no file (out of memory).
#include <gtest/gtest.h>

#include <stdexcept>

#include "io/files/InputsInUse.hpp"

using namespace dfrecon;

TEST(InputsInUse, NamesTheReadThatFailedAndEveryInputOnce) {
    // Other tests of the process may have read files before: names of its own.
    { const ReadingInput a("a.slices"); }
    {
        const ReadingInput b("b.ply");
        EXPECT_EQ(inputsInUse().reading, "b.ply");
        EXPECT_EQ(lastInput(), "b.ply");
    }
    EXPECT_EQ(inputsInUse().reading, "");  // nothing is being read
    try {
        const ReadingInput outer("stack.json");
        const ReadingInput inner("plane.png");
        throw std::bad_alloc();
    } catch (const std::bad_alloc&) {
        // The innermost read is the one that failed.
        EXPECT_EQ(inputsInUse().reading, "plane.png");
    }
    { const ReadingInput again("a.slices"); }  // a new read clears the failure
    const InputsInUse in = inputsInUse();
    EXPECT_EQ(in.reading, "");
    std::vector<std::string> ours;
    for (const std::string& f : in.inputs)
        if (f == "a.slices" || f == "b.ply" || f == "stack.json" || f == "plane.png")
            ours.push_back(f);
    EXPECT_EQ(ours, (std::vector<std::string>{"a.slices", "b.ply", "stack.json", "plane.png"}));
    EXPECT_EQ(lastInput(), "a.slices");
}
