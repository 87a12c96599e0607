// write_file_atomically from several threads at once (batch mode writes in parallel): every call gets its own
// temporary file, so concurrent writers never interleave, never fail on a vanished temporary, and leave no
// temporaries behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/atomic_file.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Content written by writer `id`: many small writes so that the writes of two threads would interleave if they
// shared a file.
std::string content_of(int id) {
  std::string s;
  for (int line = 0; line < 2000; ++line) s += "writer " + std::to_string(id) + " line " + std::to_string(line) + "\n";
  return s;
}

TEST(AtomicWriteConcurrency, SameTargetFromManyThreadsEndsWithOneWholeFile) {
  const fs::path dir = fs::temp_directory_path() / ("qc_atomic_conc_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "out.txt";
  constexpr int kThreads = 8, kRounds = 5;
  std::vector<std::string> errors(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      const std::string text = content_of(t);
      for (int r = 0; r < kRounds; ++r) {
        try {
          write_file_atomically(target.string(), [&](std::ostream& out) {
            for (std::size_t i = 0; i < text.size(); i += 64) out << text.substr(i, 64) << std::flush;
          });
        } catch (const std::exception& e) {
          errors[t] = e.what();
        }
      }
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_TRUE(errors[t].empty()) << "writer " << t << ": " << errors[t];
  // The survivor is exactly one writer's complete content, and nothing else is left in the folder.
  const std::string final_text = slurp(target);
  std::set<int> matches;
  for (int t = 0; t < kThreads; ++t)
    if (final_text == content_of(t)) matches.insert(t);
  EXPECT_EQ(matches.size(), 1u) << "the file is not one writer's whole output (" << final_text.size() << " bytes)";
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(e.path().filename(), "out.txt") << "left behind: " << e.path();
  }
  EXPECT_EQ(entries, 1);
  fs::remove_all(dir);
}

TEST(AtomicWriteConcurrency, DistinctTargetsInOneFolderGetTheirOwnContent) {
  const fs::path dir = fs::temp_directory_path() / ("qc_atomic_conc2_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  constexpr int kThreads = 6;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      write_file_atomically((dir / ("f" + std::to_string(t) + ".txt")).string(),
                            [&](std::ostream& out) { out << content_of(t); });
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(slurp(dir / ("f" + std::to_string(t) + ".txt")), content_of(t));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), kThreads);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover
