#include "pliant/io/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::ReadText;
using testing::TempDirectory;

std::vector<std::string> Entries(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFile, CommitReplacesTheTarget) {
  TempDirectory directory;
  const std::string path = directory.Write("out.csv", "old contents\n");
  {
    AtomicFile file(path);
    file.Write("new ");
    file.Write("contents\n");
    EXPECT_EQ(ReadText(path), "old contents\n");  // nothing visible before Commit
    file.Commit();
  }
  EXPECT_EQ(ReadText(path), "new contents\n");
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{"out.csv"});
}

TEST(AtomicFile, ConcurrentWritersNeverShowATemporaryAndTheLastCommitWins) {
  TempDirectory directory;
  const std::string path = directory.File("out.csv");
  AtomicFile first(path);
  AtomicFile second(path);
  // The data lives in unnamed O_TMPFILE files (tmpfs, ext4, xfs, btrfs): a
  // process killed now leaves nothing to clean up.
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{});
  first.Write("first");
  second.Write("second");
  first.Commit();
  EXPECT_EQ(ReadText(path), "first");
  second.Commit();
  EXPECT_EQ(ReadText(path), "second");
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{"out.csv"});
}

TEST(AtomicFile, WithoutCommitTheOldFileIsIntactAndNoTemporaryRemains) {
  TempDirectory directory;
  const std::string path = directory.Write("params.json", "{\"old\": true}\n");
  {
    AtomicFile file(path);
    file.Write("half a new fi");
  }
  EXPECT_EQ(ReadText(path), "{\"old\": true}\n");
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{"params.json"});
}

TEST(AtomicFile, WithoutCommitNoTargetIsCreated) {
  TempDirectory directory;
  {
    AtomicFile file(directory.File("new.csv"));
    file.Write("data");
  }
  EXPECT_TRUE(Entries(directory.path()).empty());
}

TEST(AtomicFile, MissingDirectoryThrowsNamingThePath) {
  TempDirectory directory;
  const std::string path = directory.File("no/such/dir/out.csv");
  try {
    AtomicFile file(path);
    FAIL() << "created a file in a missing directory";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    EXPECT_EQ(error.code().value(), ENOENT);
  }
}

TEST(AtomicFile, WriteFileAtomically) {
  TempDirectory directory;
  const std::string path = directory.Write("a.txt", "1");
  WriteFileAtomically(path, "22");
  EXPECT_EQ(ReadText(path), "22");
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{"a.txt"});
}

TEST(AtomicFile, RelativePathWritesInTheCurrentDirectory) {
  TempDirectory directory;
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(directory.path());
  WriteFileAtomically("relative.txt", "r");
  std::filesystem::current_path(previous);
  EXPECT_EQ(ReadText(directory.File("relative.txt")), "r");
  EXPECT_EQ(Entries(directory.path()), std::vector<std::string>{"relative.txt"});
}

}  // namespace
}  // namespace pliant::io
