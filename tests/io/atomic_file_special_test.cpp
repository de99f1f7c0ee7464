// Outputs that are not regular files: written through, never replaced
// (io/include/pliant/io/atomic_file.h).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "pliant/io/atomic_file.h"
#include "pliant/io/input_error.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TempDirectory;

TEST(AtomicFileSpecial, DevNullStaysACharacterDevice) {
  if (::geteuid() != 0) {
    GTEST_SKIP() << "only root may rename over /dev/null, which is the damage this test guards "
                    "against; run the suite as root (CI does) to check it";
  }
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  WriteFileAtomically("/dev/null", "t,q1\n0,1\n");
  struct stat after {};
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_rdev, before.st_rdev);
  EXPECT_EQ(after.st_ino, before.st_ino);
}

TEST(AtomicFileSpecial, AFifoIsWrittenThroughToItsReader) {
  TempDirectory directory;
  const std::string fifo = directory.File("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = ReadText(fifo); });
  {
    AtomicFile file(fifo);
    EXPECT_TRUE(file.writes_through());
    file.Write("t,q1\n");
    file.Write("0,0.25\n");
    file.Commit();
  }
  reader.join();
  EXPECT_EQ(received, "t,q1\n0,0.25\n");
  struct stat status {};
  ASSERT_EQ(::lstat(fifo.c_str(), &status), 0);
  EXPECT_TRUE(S_ISFIFO(status.st_mode));
}

TEST(AtomicFileSpecial, ASymlinkKeepsItsLinkAndItsTargetIsReplaced) {
  TempDirectory directory;
  fs::create_directories(directory.path() / "real");
  const std::string target = directory.Write("real/out.csv", "old\n");
  const std::string link = directory.File("link.csv");
  fs::create_symlink("real/out.csv", link);  // relative, as users make them
  {
    AtomicFile file(link);
    EXPECT_FALSE(file.writes_through());
    file.Write("new\n");
    EXPECT_EQ(ReadText(target), "old\n");  // still atomic: nothing before Commit
    file.Commit();
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(fs::read_symlink(link), fs::path("real/out.csv"));
  EXPECT_EQ(ReadText(target), "new\n");
  EXPECT_EQ(ReadText(link), "new\n");
  // No temporary left beside the link or the target.
  EXPECT_EQ(std::distance(fs::directory_iterator(directory.path() / "real"), {}), 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(directory.path()), {}), 2);
}

TEST(AtomicFileSpecial, ADanglingSymlinkCreatesItsTarget) {
  TempDirectory directory;
  const std::string link = directory.File("link.csv");
  fs::create_symlink(directory.File("made.csv"), link);
  WriteFileAtomically(link, "made\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(ReadText(directory.File("made.csv")), "made\n");
}

TEST(AtomicFileSpecial, ASymlinkToAFifoWritesThroughIt) {
  TempDirectory directory;
  const std::string fifo = directory.File("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string link = directory.File("link");
  fs::create_symlink(fifo, link);
  std::string received;
  std::thread reader([&] { received = ReadText(fifo); });
  WriteFileAtomically(link, "through\n");
  reader.join();
  EXPECT_EQ(received, "through\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(AtomicFileSpecial, ADirectoryIsRefusedNamingThePathAndWhatToGive) {
  TempDirectory directory;
  const std::string path = directory.File("sub");
  fs::create_directories(path);
  try {
    AtomicFile file(path);
    FAIL() << "opened a directory as an output";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), path);
    EXPECT_EQ(error.problem(), "the output is a directory");
    EXPECT_NE(error.fix().find("/dev/null"), std::string::npos) << error.fix();
  }
  EXPECT_TRUE(fs::is_directory(path));
}

TEST(AtomicFileSpecial, ALoopOfSymlinksIsRefused) {
  TempDirectory directory;
  const std::string a = directory.File("a"), b = directory.File("b");
  fs::create_symlink(b, a);
  fs::create_symlink(a, b);
  EXPECT_THROW(WriteFileAtomically(a, "x"), InputError);
  EXPECT_TRUE(fs::is_symlink(a));
}

TEST(AtomicFileSpecial, DashWritesStandardOutput) {
  TempDirectory directory;
  const std::string captured = directory.File("stdout.txt");
  std::fflush(stdout);
  const int saved = ::dup(STDOUT_FILENO);
  const int fd = ::open(captured.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(fd, 0);
  ::dup2(fd, STDOUT_FILENO);
  ::close(fd);
  {
    AtomicFile file("-");
    EXPECT_TRUE(file.writes_through());
    file.Write("to stdout\n");
    file.Commit();
  }
  ::dup2(saved, STDOUT_FILENO);
  ::close(saved);
  EXPECT_EQ(ReadText(captured), "to stdout\n");
  EXPECT_FALSE(fs::exists(directory.File("-")));
}

}  // namespace
}  // namespace pliant::io
