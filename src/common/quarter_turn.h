#pragma once
// Quarter turns: a matching, a transition rotation or a branch point's quarter index counts turns by i, so only its
// class modulo 4 acts (thesis 3.1).

namespace quadcover {

/// k modulo 4 in {0, 1, 2, 3}, also for negative k. \pre none
constexpr int mod4(int k) { return ((k % 4) + 4) % 4; }

}  // namespace quadcover
