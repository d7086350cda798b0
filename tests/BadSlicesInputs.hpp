#pragma once
// Malformed .slices inputs, one per error class the parser reports, with the
// line and message each must produce. Shared by the parser and CLI tests.
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon::testing {

inline const std::string kHeader = "dfrecon-slices 1\nunits mm\n";
inline const std::string kSquare = "contour 4\n0 0\n10 0\n10 10\n0 10\n";

struct BadInput {
    const char* name;
    std::string text;
    int line;
    const char* message;  // substring of the problem
};

// Lets GoogleTest print the case's name instead of its bytes.
inline void PrintTo(const BadInput& input, std::ostream* out) {
    *out << input.name;
}

// Two meanders of `teeth` long strokes each over one square, one's strokes
// upright, the other's lying: every upright stroke crosses every lying one
// (teeth² crossings), more than any reading combines from 224 teeth on.
inline std::vector<Polygon> crossingMeanders(int teeth) {
    const double top = 2.0 * teeth;  // strokes run from -1 to top + 1
    auto meander = [&](bool upright) {
        Polygon points;
        auto add = [&](double across, double along) {
            points.push_back(upright ? Point2{across, along} : Point2{along, across});
        };
        for (int k = 0; k < teeth; ++k) {
            const double across = upright ? 2 * k : 2 * k + 0.5;
            add(across, k % 2 ? top + 1 : -1);
            add(across, k % 2 ? -1 : top + 1);
        }
        // Back to the start well outside the other meander's strokes.
        const double end = teeth % 2 ? top + 1 : -1;
        add(top + 3, end);
        add(top + 3, -5);
        add(-5, -5);
        return points;
    };
    return {meander(true), meander(false)};
}

// crossingMeanders as .slices contour lines.
inline std::string crossingCombs(int teeth) {
    std::string text;
    for (const Polygon& contour : crossingMeanders(teeth)) {
        text += "contour " + std::to_string(contour.size()) + "\n";
        for (const Point2 p : contour)
            text += std::to_string(p.x) + " " + std::to_string(p.y) + "\n";
    }
    return text;
}

inline std::vector<BadInput> badInputs() {
    return {
        {"EmptyFile", "", 0, "empty file"},
        {"OnlyComments", "# nothing\n\n", 2, "empty file"},
        {"BadHeader", "slices 1\nunits mm\n", 1, "bad header"},
        {"BadVersion", "dfrecon-slices 2\nunits mm\n", 1, "unsupported version '2'"},
        {"MissingUnits", "dfrecon-slices 1\nroi a\n", 2, "expected 'units mm'"},
        {"WrongUnits", "dfrecon-slices 1\nunits cm\n", 2, "unsupported units 'cm'"},
        {"NonNumericX", kHeader + "roi a\nslice 0\ncontour 3\n0 0\nabc 0\n1 1\n", 7,
         "'abc' is not a number"},
        {"NonNumericZ", kHeader + "roi a\nslice 1.5mm\n", 4, "'1.5mm' is not a number"},
        {"NaN", kHeader + "roi a\nslice 0\ncontour 3\n0 0\n1 nan\n1 1\n", 7, "NaN or Inf"},
        {"Inf", kHeader + "roi a\nslice inf\n", 4, "NaN or Inf"},
        {"OutOfRange", kHeader + "roi a\nslice 1e400\n", 4, "out of range"},
        {"HugeCoordinate", kHeader + "roi a\nslice 0\ncontour 3\n0 0\n1e9 0\n1 1\n", 7,
         "exceeds the limit"},
        // Contours crossing in more places than the even-odd fill combines.
        {"CrossingsPastTheLimit", kHeader + "roi a\nslice 0\n" + crossingCombs(300), 4,
         "more than the exclusive or combines"},
        {"CountTooLarge", kHeader + "roi a\nslice 0\ncontour 5\n0 0\n1 0\n1 1\nslice 1\n", 5,
         "declares 5 points but 3 follow"},
        {"CountTooLargeAtEof", kHeader + "roi a\nslice 0\ncontour 5\n0 0\n1 0\n1 1\n", 5,
         "declares 5 points but 3 follow"},
        {"CountTooSmall", kHeader + "roi a\nslice 0\ncontour 3\n0 0\n1 0\n1 1\n0 1\n", 9,
         "declares 3 points but more follow"},
        {"NegativeCount", kHeader + "roi a\nslice 0\ncontour -3\n", 5, "point count -3 outside"},
        {"PointWithThreeNumbers", kHeader + "roi a\nslice 0\ncontour 3\n0 0 0\n", 6,
         "expected a point 'x y', got 3 tokens"},
        {"SliceBeforeRoi", kHeader + "slice 0\n", 3, "'slice' before any 'roi'"},
        {"ContourBeforeSlice", kHeader + "roi a\n" + kSquare, 4, "'contour' before any 'slice'"},
        {"UnknownKeyword", kHeader + "roi a\npolygon 3\n", 4, "unknown keyword 'polygon'"},
        {"KeywordCase", kHeader + "ROI a\n", 3, "unknown keyword 'ROI'"},
        {"DuplicateRoi", kHeader + "roi a\nroi a\n", 4, "duplicate ROI name 'a' (first at line 3)"},
        {"BadColour", kHeader + "roi a 255 0 300\n", 3, "blue 300 outside 0..255"},
        {"UnterminatedQuote", kHeader + "roi \"left lung\n", 3, "unterminated quoted name"},
        {"SecondHeader", kHeader + "dfrecon-slices 1\n", 3, "may appear only once"},
        {"NulByte", kHeader + std::string("roi a\0b\n", 8), 3, "NUL byte"},
    };
}

}  // namespace dfrecon::testing
