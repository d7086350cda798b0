#pragma once
// Dice and Jaccard from three volumes (or areas), one definition for every
// overlap compare reports: on the surfaces, and on the planes.

namespace dfrecon {

/// 2|A ∩ B| / (|A| + |B|); 1 for two empty structures.
inline double diceOf(double volumeA, double volumeB, double intersection) {
    const double total = volumeA + volumeB;
    return total > 0 ? 2 * intersection / total : 1.0;
}

/// |A ∩ B| / |A ∪ B|; 1 for two empty structures.
inline double jaccardOf(double volumeA, double volumeB, double intersection) {
    const double all = volumeA + volumeB - intersection;
    return all > 0 ? intersection / all : 1.0;
}

}  // namespace dfrecon
