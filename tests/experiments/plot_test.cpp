#include "pliant/experiments/plot.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;

Figure TwoPanels() {
  Figure figure{"test figure", {}};
  figure.panels.push_back({"a \"quoted\" title", "x (rad)", "y (N·m)", {}});
  figure.panels[0].series.push_back({"points", {0.0, 1.0, 2.0}, {0.0, 1.0, 4.0}});
  figure.panels[0].series.push_back({"line", {0.0, 2.0}, {0.0, 4.0}, "lines lw 2"});
  figure.panels.push_back({"empty", "x", "y", {}});
  return figure;
}

TEST(Plot, GnuplotDrawsAPngWithItsSources) {
  if (FindGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = fs::temp_directory_path() / "pliant_plot_test";
  fs::create_directories(dir);
  const std::string png = (dir / "figure.png").string();
  WriteFigure(TwoPanels(), png, /*keep_sources=*/true);
  std::ifstream in(png, std::ios::binary);
  char signature[4] = {};
  in.read(signature, 4);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  EXPECT_TRUE(fs::exists(png + ".gp"));
  EXPECT_TRUE(fs::exists(png + ".dat"));
  fs::remove_all(dir);
}

TEST(Plot, MissingGnuplotSaysHowToInstallIt) {
  setenv("PLIANT_GNUPLOT", "/nonexistent/gnuplot", 1);
  try {
    WriteFigure(TwoPanels(), "never.png");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install gnuplot-nox"), std::string::npos)
        << e.what();
  }
  unsetenv("PLIANT_GNUPLOT");
  EXPECT_FALSE(fs::exists("never.png"));
}

TEST(Plot, RefusesAnUnknownPictureFormat) {
  if (FindGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed";
  EXPECT_THROW(WriteFigure(TwoPanels(), "figure.jpg"), std::runtime_error);
}

}  // namespace
}  // namespace pliant::experiments
