// closest_match, the "did you mean" of every reader: hand-checked suggestions, and the pruned search
// against the whole edit-distance table for every candidate, on random words short and long.
#include "glint/base/diagnostics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace glint {
namespace {

// The Levenshtein distance from the whole table, the textbook way.
std::size_t distance(const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j)
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    return d[a.size()][b.size()];
}

// The rule closest_match documents, by brute force: the first candidate of least distance, if
// that distance is at most max(2, a third of the word's length).
std::string brute_force(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const std::string& c : candidates)
        if (const std::size_t d = distance(word, c); d < best_distance) best_distance = d, best = c;
    return best;
}

TEST(ClosestMatch, SuggestsTyposAndNothingForStrangers) {
    const std::vector<std::string> shapes{"sphere", "plane", "quad", "mesh", "disk", "cylinder"};
    EXPECT_EQ(closest_match("spehre", shapes), "sphere");  // two edits
    EXPECT_EQ(closest_match("mesj", shapes), "mesh");
    EXPECT_EQ(closest_match("cylindre", shapes), "cylinder");
    EXPECT_EQ(closest_match("teapot", shapes), "");
    EXPECT_EQ(closest_match(std::string(5000, 'x') + "sphere", shapes), "");
    EXPECT_EQ(closest_match("", {"a", "abcd"}), "a");  // distance 1 is within 2
}

TEST(ClosestMatch, AgreesWithTheWholeTableOnRandomWords) {
    std::mt19937 rng(7);
    const auto word = [&](std::size_t max_len) {
        std::string w(std::uniform_int_distribution<std::size_t>(0, max_len)(rng), ' ');
        for (char& ch : w) ch = "abcde"[rng() % 5];  // a small alphabet, so that words come close
        return w;
    };
    int suggested = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<std::string> candidates;
        for (int k = 0, n = 1 + static_cast<int>(rng() % 8); k < n; ++k) candidates.push_back(word(12));
        const std::string w = trial % 10 == 0 ? word(80) : word(14);
        const std::string expected = brute_force(w, candidates);
        ASSERT_EQ(closest_match(w, candidates), expected) << "word '" << w << "'";
        suggested += !expected.empty();
    }
    EXPECT_GT(suggested, 300);  // the comparison saw many suggestions, not only empty answers
}

}  // namespace
}  // namespace glint
