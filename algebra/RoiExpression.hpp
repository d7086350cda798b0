#pragma once
// Structure expressions as planning systems write them: "Ring = (PTV + 20) -
// (PTV + 3)", "PTV_eval = PTV - Rectum", "Parotids = Parotid_L | Parotid_R".
// Parsed into a tree, then lowered to a form whose every margin sits on an
// ROI, the only place a margin is exact for the field algebra of
// algebra/SolidField (a margin of an ROI is a level of its distance; a
// margin of a union is the union of the margins; of an intersection, only
// for a shrink).
//
// Grammar (spaces anywhere between tokens):
//   definition := NAME '=' expr
//   expr       := term (('|' | '+' | '-' | '^') term)*      union, union, difference, xor
//   term       := operand ('&' operand)*                    intersection
//   operand    := ( '(' expr ')' | ROI ) margin*
//   margin     := ('+' | '-') (NUMBER ['mm'] | '[' R ',' L ',' A ',' P ',' S ',' I ']')
// '+' or '-' followed by a number or a bracket is a margin of the operand
// before it (grow or shrink, mm); followed by anything else it is union or
// difference. An ROI is the longest name of the structure set that starts
// there (so "PTV-70" is the ROI when the set has one), or a name in quotes
// ('...' or "...").
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace dfrecon {

/// A margin in mm along each patient direction, in the order planning
/// systems list them: right, left, anterior, posterior, superior, inferior.
/// All ≥ 0 for a growth, all ≤ 0 for a shrink; an isotropic margin has six
/// equal values.
struct DirectionalMargin {
    std::array<double, 6> mm{0, 0, 0, 0, 0, 0};

    static DirectionalMargin uniform(double mm) { return {{mm, mm, mm, mm, mm, mm}}; }
    bool isZero() const;
    bool isUniform() const;
    bool grows() const;    // some value > 0 (then none < 0)
    bool shrinks() const;  // some value < 0 (then none > 0)
    /// The same along both senses of each axis (an ellipsoid, not eight
    /// octants of different ones).
    bool isSymmetric() const;
    /// "5 mm" or "[R 5, L 5, A 7, P 7, S 10, I 10] mm".
    std::string text() const;
};

/// One node of an expression: an ROI, an operation on two nodes, or a
/// margin of one.
struct ExpressionNode {
    enum class Kind { Roi, Union, Intersection, Difference, Xor, Margin };
    Kind kind = Kind::Roi;
    std::string roi;                  // Kind::Roi
    std::size_t left = 0, right = 0;  // indices of the operands (Margin: left only)
    DirectionalMargin margin;         // Kind::Margin
};

/// A parsed definition: the new ROI's name and its expression, a tree whose
/// root is nodes[root].
struct RoiExpression {
    std::string name;
    std::vector<ExpressionNode> nodes;
    std::size_t root = 0;

    /// The ROIs it reads, each once, in order of first use.
    std::vector<std::string> rois() const;
    /// The expression written back with every parenthesis explicit.
    std::string text() const;
};

/// A definition that does not parse, or names an ROI the set lacks: what()
/// says what and where, as "column N: problem".
class ExpressionError : public std::invalid_argument {
  public:
    ExpressionError(std::size_t column, const std::string& problem);
    std::size_t column() const { return column_; }

  private:
    std::size_t column_;
};

/// The new ROI's name of a definition "NAME = EXPR" (trimmed), as
/// parseRoiExpression reads it; "" without '='. For checking the name before
/// the structure set is read. O(length).
std::string roiExpressionName(const std::string& definition);

/// The name `margin` and Python's margin() give a new ROI by default:
/// "ROI+5", "ROI-3" (mm, rounded), "ROI+margin" for one per direction.
std::string marginRoiName(const std::string& roi, const DirectionalMargin& margin);

/// Most ROIs, margins and operations in one expression, and deepest
/// nesting of parentheses: far beyond what planning systems write, well
/// within memory and stack.
inline constexpr std::size_t kMaxExpressionNodes = 1000;
inline constexpr std::size_t kMaxExpressionDepth = 100;

/// Parses "NAME = EXPR" against the names of a structure set. Throws
/// ExpressionError for a syntax error, an unknown ROI (naming the closest
/// known ones), a margin whose values mix growth and shrinkage, a margin
/// beyond ±200 mm, more than kMaxExpressionNodes nodes or parentheses
/// nested deeper than kMaxExpressionDepth, or an empty or over-long (> 64
/// bytes) name. O(length × names).
RoiExpression parseRoiExpression(const std::string& definition,
                                 const std::vector<std::string>& roiNames);

/// The same expression with its margins moved onto the ROIs: a margin of a
/// union becomes the union of margins (any growth or shrink), a shrink of an
/// intersection the intersection of shrinks, and two nested margins of one
/// sense and uniform add up; afterwards every Kind::Margin node's operand is
/// a Kind::Roi node. Throws ExpressionError (column 0) for nested margins
/// that add up beyond ±200 mm, and for a margin of
/// anything else (a difference, an exclusive or, a growth of an
/// intersection, a shrink of a union, a shrink of a growth), none of which
/// is a level of the operands' distances: give that result a name first,
/// then grow it. O(nodes · depth).
RoiExpression marginsOnRois(const RoiExpression& expression);

}  // namespace dfrecon
