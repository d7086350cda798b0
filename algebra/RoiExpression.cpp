#include "algebra/RoiExpression.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>

namespace dfrecon {

namespace {

constexpr double kMaxMarginMm = 200;
constexpr std::size_t kMaxNameBytes = 64;  // DICOM ROIName is an LO

bool isSpace(char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0;
}

std::string trimmed(const std::string& s) {
    std::size_t first = 0, last = s.size();
    while (first < last && isSpace(s[first])) ++first;
    while (last > first && isSpace(s[last - 1])) --last;
    return s.substr(first, last - first);
}

// Levenshtein distance, for "did you mean".
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// A recursive-descent parser over the text after '='; columns are 1-based
// in the whole definition.
class Parser {
  public:
    Parser(std::string text, std::size_t offset, const std::vector<std::string>& names)
        : text_(std::move(text)), offset_(offset), names_(names) {}

    RoiExpression parse(std::string name) {
        RoiExpression e;
        e.name = std::move(name);
        nodes_ = &e.nodes;
        e.root = expr();
        skipSpaces();
        if (at_ < text_.size()) fail("unexpected '" + std::string(1, text_[at_]) + "'");
        return e;
    }

  private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw ExpressionError(offset_ + at_ + 1, problem);
    }
    void skipSpaces() {
        while (at_ < text_.size() && isSpace(text_[at_])) ++at_;
    }
    bool peek(char c) {
        skipSpaces();
        return at_ < text_.size() && text_[at_] == c;
    }
    std::size_t add(ExpressionNode node) {
        // Every node costs a field or a surface when evaluated: an
        // expression of thousands would run out of memory, not answer.
        if (nodes_->size() >= kMaxExpressionNodes)
            fail("more than " + std::to_string(kMaxExpressionNodes) +
                 " ROIs, margins and operations in one expression; define parts first (one "
                 "combine each)");
        nodes_->push_back(std::move(node));
        return nodes_->size() - 1;
    }
    std::size_t binary(ExpressionNode::Kind kind, std::size_t left, std::size_t right) {
        ExpressionNode n;
        n.kind = kind;
        n.left = left;
        n.right = right;
        return add(n);
    }

    std::size_t expr() {
        std::size_t left = term();
        for (;;) {
            skipSpaces();
            if (at_ >= text_.size()) return left;
            const char c = text_[at_];
            ExpressionNode::Kind kind;
            if (c == '|' || c == '+')
                kind = ExpressionNode::Kind::Union;
            else if (c == '-')
                kind = ExpressionNode::Kind::Difference;
            else if (c == '^')
                kind = ExpressionNode::Kind::Xor;
            else
                return left;
            ++at_;
            left = binary(kind, left, term());
        }
    }

    std::size_t term() {
        std::size_t left = operand();
        while (peek('&')) {
            ++at_;
            left = binary(ExpressionNode::Kind::Intersection, left, operand());
        }
        return left;
    }

    std::size_t operand() {
        skipSpaces();
        std::size_t node;
        if (peek('(')) {
            // The parser recurses once per parenthesis: bounded here, not by
            // the stack.
            if (++depth_ > kMaxExpressionDepth)
                fail("parentheses nested deeper than " + std::to_string(kMaxExpressionDepth));
            ++at_;
            node = expr();
            if (!peek(')')) fail("expected ')'");
            ++at_;
            --depth_;
        } else {
            node = roi();
        }
        // Margins of this operand: a sign followed by a number or '['.
        for (;;) {
            skipSpaces();
            if (at_ + 1 > text_.size() || (text_[at_] != '+' && text_[at_] != '-')) return node;
            std::size_t next = at_ + 1;
            while (next < text_.size() && isSpace(text_[next])) ++next;
            const bool number =
                next < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[next])) ||
                                        text_[next] == '.' || text_[next] == '[');
            if (!number) return node;
            const double sign = text_[at_] == '+' ? 1 : -1;
            at_ = next;
            ExpressionNode m;
            m.kind = ExpressionNode::Kind::Margin;
            m.left = node;
            m.margin = margin(sign);
            node = add(m);
        }
    }

    double number() {
        skipSpaces();
        const std::size_t start = at_;
        while (at_ < text_.size() &&
               (std::isdigit(static_cast<unsigned char>(text_[at_])) || text_[at_] == '.'))
            ++at_;
        const std::string digits = text_.substr(start, at_ - start);
        char* end = nullptr;
        const double value = std::strtod(digits.c_str(), &end);
        if (digits.empty() || end != digits.c_str() + digits.size() || !std::isfinite(value)) {
            at_ = start;
            fail("expected a margin in mm");
        }
        if (text_.compare(at_, 2, "mm") == 0) at_ += 2;
        if (value > kMaxMarginMm) {
            at_ = start;
            fail("a margin of " + digits + " mm is beyond the 200 mm allowed");
        }
        return value;
    }

    DirectionalMargin margin(double sign) {
        if (!peek('[')) return DirectionalMargin::uniform(sign * number());
        ++at_;
        DirectionalMargin m;
        for (std::size_t k = 0; k < 6; ++k) {
            if (k > 0) {
                if (!peek(',')) fail("expected ',' between the six margins R,L,A,P,S,I");
                ++at_;
            }
            m.mm[k] = sign * number();
        }
        if (!peek(']')) fail("expected ']' after the six margins R,L,A,P,S,I");
        ++at_;
        return m;
    }

    std::size_t roi() {
        skipSpaces();
        const std::size_t start = at_;
        if (at_ < text_.size() && (text_[at_] == '\'' || text_[at_] == '"')) {
            const char quote = text_[at_];
            const std::size_t close = text_.find(quote, at_ + 1);
            if (close == std::string::npos) fail("unterminated quote");
            const std::string name = text_.substr(at_ + 1, close - at_ - 1);
            if (std::find(names_.begin(), names_.end(), name) == names_.end()) fail(unknown(name));
            at_ = close + 1;
            return leaf(name);
        }
        // The longest ROI name starting here.
        std::size_t best = 0;
        const std::string* found = nullptr;
        for (const std::string& name : names_)
            if (!name.empty() && name.size() > best && text_.compare(at_, name.size(), name) == 0) {
                best = name.size();
                found = &name;
            }
        // A name that runs on into letters or digits ("PTVX") is not that
        // name but an unknown one.
        const auto continuesWord = [&](std::size_t end) {
            return end < text_.size() &&
                   (std::isalnum(static_cast<unsigned char>(text_[end])) || text_[end] == '_');
        };
        if (found && !continuesWord(at_ + best)) {
            at_ += best;
            return leaf(*found);
        }
        std::size_t end = at_;
        while (end < text_.size() && !isSpace(text_[end]) &&
               std::string("()|&^+-=[],").find(text_[end]) == std::string::npos)
            ++end;
        if (end == start)
            fail(at_ < text_.size() ? "expected an ROI name"
                                    : "expected an ROI name, found the end");
        fail(unknown(text_.substr(start, end - start)));
    }

    std::string unknown(const std::string& name) const {
        std::vector<std::pair<std::size_t, std::string>> near;
        for (const std::string& n : names_) near.push_back({editDistance(name, n), n});
        std::sort(near.begin(), near.end());
        std::string text = "no ROI named '" + name + "' in the structure set";
        if (!near.empty()) {
            text += " (closest: ";
            for (std::size_t k = 0; k < near.size() && k < 3; ++k)
                text += (k ? ", '" : "'") + near[k].second + "'";
            text += "; quote a name with spaces or operators in it)";
        }
        return text;
    }

    std::size_t leaf(const std::string& name) {
        ExpressionNode n;
        n.kind = ExpressionNode::Kind::Roi;
        n.roi = name;
        return add(n);
    }

    const std::string text_;
    std::size_t offset_;
    const std::vector<std::string>& names_;
    std::vector<ExpressionNode>* nodes_ = nullptr;
    std::size_t at_ = 0;
    std::size_t depth_ = 0;  // parentheses open at at_
};

std::string numberText(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

ExpressionError::ExpressionError(std::size_t column, const std::string& problem)
    : std::invalid_argument(column ? "column " + std::to_string(column) + ": " + problem : problem),
      column_(column) {}

bool DirectionalMargin::isZero() const {
    return std::all_of(mm.begin(), mm.end(), [](double v) { return v == 0; });
}
bool DirectionalMargin::isUniform() const {
    return std::all_of(mm.begin(), mm.end(), [&](double v) { return v == mm[0]; });
}
bool DirectionalMargin::grows() const {
    return std::any_of(mm.begin(), mm.end(), [](double v) { return v > 0; });
}
bool DirectionalMargin::shrinks() const {
    return std::any_of(mm.begin(), mm.end(), [](double v) { return v < 0; });
}
bool DirectionalMargin::isSymmetric() const {
    return mm[0] == mm[1] && mm[2] == mm[3] && mm[4] == mm[5];
}
std::string DirectionalMargin::text() const {
    if (isUniform()) return numberText(mm[0]) + " mm";
    static const char* kDirections[6] = {"R", "L", "A", "P", "S", "I"};
    std::string t = "[";
    for (std::size_t k = 0; k < 6; ++k)
        t += (k ? ", " : "") + std::string(kDirections[k]) + " " + numberText(mm[k]);
    return t + "] mm";
}

std::vector<std::string> RoiExpression::rois() const {
    std::vector<std::string> names;
    const std::function<void(std::size_t)> visit = [&](std::size_t i) {
        const ExpressionNode& n = nodes[i];
        if (n.kind == ExpressionNode::Kind::Roi) {
            if (std::find(names.begin(), names.end(), n.roi) == names.end()) names.push_back(n.roi);
            return;
        }
        visit(n.left);
        if (n.kind != ExpressionNode::Kind::Margin) visit(n.right);
    };
    if (!nodes.empty()) visit(root);
    return names;
}

std::string RoiExpression::text() const {
    const std::function<std::string(std::size_t)> write = [&](std::size_t i) -> std::string {
        const ExpressionNode& n = nodes[i];
        switch (n.kind) {
            case ExpressionNode::Kind::Roi:
                return "'" + n.roi + "'";
            case ExpressionNode::Kind::Margin: {
                const bool shrink = n.margin.shrinks();
                DirectionalMargin size = n.margin;
                for (double& v : size.mm) v = std::abs(v);
                return "(" + write(n.left) + (shrink ? " - " : " + ") + size.text() + ")";
            }
            case ExpressionNode::Kind::Union:
                return "(" + write(n.left) + " | " + write(n.right) + ")";
            case ExpressionNode::Kind::Intersection:
                return "(" + write(n.left) + " & " + write(n.right) + ")";
            case ExpressionNode::Kind::Difference:
                return "(" + write(n.left) + " - " + write(n.right) + ")";
            case ExpressionNode::Kind::Xor:
                return "(" + write(n.left) + " ^ " + write(n.right) + ")";
        }
        return {};
    };
    return nodes.empty() ? std::string() : write(root);
}

std::string roiExpressionName(const std::string& definition) {
    const std::size_t equals = definition.find('=');
    return equals == std::string::npos ? std::string() : trimmed(definition.substr(0, equals));
}

std::string marginRoiName(const std::string& roi, const DirectionalMargin& margin) {
    return roi + (margin.shrinks() ? "-" : "+") +
           (margin.isUniform() ? std::to_string(int(std::lround(std::abs(margin.mm[0]))))
                               : std::string("margin"));
}

RoiExpression parseRoiExpression(const std::string& definition,
                                 const std::vector<std::string>& roiNames) {
    const std::size_t equals = definition.find('=');
    if (equals == std::string::npos)
        throw ExpressionError(
            1, "expected NAME = EXPRESSION (e.g. \"Ring = (PTV + 20) - (PTV + 3)\")");
    const std::string name = roiExpressionName(definition);
    if (name.empty()) throw ExpressionError(1, "the new ROI has no name before '='");
    if (name.size() > kMaxNameBytes)
        throw ExpressionError(1, "the new ROI's name is longer than DICOM's 64 characters");
    Parser parser(definition.substr(equals + 1), equals + 1, roiNames);
    return parser.parse(name);
}

RoiExpression marginsOnRois(const RoiExpression& expression) {
    RoiExpression out;
    out.name = expression.name;
    using Kind = ExpressionNode::Kind;
    // Rebuilds node i of `expression` with `margin` applied to it (zero: none).
    const std::function<std::size_t(std::size_t, const DirectionalMargin&)> lower =
        [&](std::size_t i, const DirectionalMargin& margin) -> std::size_t {
        const ExpressionNode& n = expression.nodes[i];
        const auto push = [&](ExpressionNode node) {
            out.nodes.push_back(std::move(node));
            return out.nodes.size() - 1;
        };
        switch (n.kind) {
            case Kind::Roi: {
                const std::size_t leaf = push(n);
                if (margin.isZero()) return leaf;
                ExpressionNode m;
                m.kind = Kind::Margin;
                m.left = leaf;
                m.margin = margin;
                return push(m);
            }
            case Kind::Margin: {
                if (margin.isZero()) return lower(n.left, n.margin);
                const bool sameSense = (margin.grows() && n.margin.grows()) ||
                                       (margin.shrinks() && n.margin.shrinks());
                if (!sameSense || !margin.isUniform() || !n.margin.isUniform())
                    throw ExpressionError(0, "a margin of " + margin.text() +
                                                 " around a margin of " + n.margin.text() +
                                                 " is not one margin; name the inner result first "
                                                 "(one combine), then add the outer margin");
                const double sumMm = margin.mm[0] + n.margin.mm[0];
                if (std::abs(sumMm) > kMaxMarginMm)
                    throw ExpressionError(0, "margins of " + margin.text() + " and " +
                                                 n.margin.text() + " add up to " +
                                                 numberText(sumMm) +
                                                 " mm, beyond the 200 mm allowed");
                return lower(n.left, DirectionalMargin::uniform(sumMm));
            }
            case Kind::Union:
            case Kind::Intersection:
            case Kind::Difference:
            case Kind::Xor: {
                const bool distributes = margin.isZero() ||
                                         (n.kind == Kind::Union && margin.grows()) ||
                                         (n.kind == Kind::Intersection && margin.shrinks());
                if (!distributes) {
                    static const char* kWhat[] = {"",           "union",        "intersection",
                                                  "difference", "exclusive or", ""};
                    throw ExpressionError(
                        0, std::string("a ") + (margin.grows() ? "growth" : "shrink") + " of " +
                               margin.text() + " of a" +
                               (n.kind == Kind::Intersection ? "n " : " ") + kWhat[int(n.kind)] +
                               " is not a level of its ROIs' distances; name the " +
                               kWhat[int(n.kind)] + " first (one combine), then apply the margin");
                }
                ExpressionNode node = n;
                node.left = lower(n.left, margin);
                node.right = lower(n.right, margin);
                return push(node);
            }
        }
        return 0;
    };
    out.root = lower(expression.root, DirectionalMargin{});
    return out;
}

}  // namespace dfrecon
