#pragma once
// What the ROI expression parser must do with any text (algebra/RoiExpression),
// shared by the fuzz target and the test that replays its corpus: parse it or
// throw ExpressionError, never anything else, crash or hang; a parsed
// expression is a tree (every operand an earlier node, the root the last)
// within the documented bounds; lowering its margins onto ROIs succeeds or
// throws ExpressionError, and afterwards every margin's operand is an ROI
// and no margin is beyond 200 mm.
#include <string>
#include <vector>

#include "algebra/RoiExpression.hpp"

namespace dfrecon::fuzzing {

/// The names the oracle's structure set holds: plain, with an operator in
/// it (matched longest first) and with a space (quoted).
inline const std::vector<std::string>& expressionRoiNames() {
    static const std::vector<std::string> names{"PTV", "PTV-70", "CTV", "Lung L", "Cord"};
    return names;
}

/// Checks one definition; returns false where the parser breaks a rule
/// above (the fuzz target traps, the test fails).
inline bool expressionHolds(const std::string& definition) {
    RoiExpression parsed;
    try {
        parsed = parseRoiExpression(definition, expressionRoiNames());
    } catch (const ExpressionError&) {
        return true;
    }
    auto isTree = [](const RoiExpression& e) {
        if (e.nodes.empty() || e.root >= e.nodes.size()) return false;
        for (std::size_t i = 0; i < e.nodes.size(); ++i) {
            const ExpressionNode& n = e.nodes[i];
            if (n.kind == ExpressionNode::Kind::Roi) continue;
            if (n.left >= i) return false;
            if (n.kind != ExpressionNode::Kind::Margin && n.right >= i) return false;
        }
        return true;
    };
    if (!isTree(parsed) || parsed.nodes.size() > kMaxExpressionNodes) return false;
    try {
        const RoiExpression lowered = marginsOnRois(parsed);
        if (!isTree(lowered)) return false;
        for (const ExpressionNode& node : lowered.nodes) {
            if (node.kind != ExpressionNode::Kind::Margin) continue;
            if (lowered.nodes[node.left].kind != ExpressionNode::Kind::Roi) return false;
            for (const double mm : node.margin.mm)
                if (!(mm >= -200 && mm <= 200)) return false;
        }
    } catch (const ExpressionError&) {
    }
    return true;
}

}  // namespace dfrecon::fuzzing
