// load_scene_set_csv: an exploration's scenes (curio-lab run --save-scenes) as a training set.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "host_tools/vae/scene_set.hpp"

namespace fs = std::filesystem;

namespace curio::train {
namespace {

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::path(CURIO_TEST_WORK_DIR) / name;
  std::ofstream(p) << text;
  return p;
}

// The message of the runtime_error loading `text` throws ("" if none).
std::string load_error(const std::string& text) {
  const fs::path p = write_file("scenes_bad.csv", text);
  try {
    load_scene_set_csv(p.string(), 1);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

constexpr const char* kHeader = "episode,ball_x,ball_y,distractor_x,distractor_y\n";

TEST(LoadSceneSetCsv, FactorsAndImagesRoundTripThroughTheFile) {
  // Scenes written the way curio-lab writes them (%.9g) read back to the same floats, and
  // render to the same images as the uniform set they came from.
  const SceneSet uniform = render_scene_set(5, 7, 3, 1);
  std::string text = kHeader;
  const float* f = uniform.factors.data_ptr<float>();
  char row[128];
  for (int i = 0; i < 5; ++i) {
    std::snprintf(row, sizeof row, "%d,%.9g,%.9g,%.9g,%.9g\r\n", i, double(f[4 * i]),
                  double(f[4 * i + 1]), double(f[4 * i + 2]), double(f[4 * i + 3]));
    text += row;
  }
  text += "\n";  // a trailing blank line is ignored
  const SceneSet loaded = load_scene_set_csv(write_file("scenes_good.csv", text).string(), 2);
  ASSERT_EQ(loaded.factors.sizes(), uniform.factors.sizes());
  EXPECT_TRUE(torch::equal(loaded.factors, uniform.factors));
  ASSERT_EQ(loaded.images.sizes(), uniform.images.sizes());
  EXPECT_TRUE(torch::equal(loaded.images, uniform.images));
  EXPECT_GT(loaded.images.sum().item<int64_t>(), 0);
}

TEST(LoadSceneSetCsv, ABadFileIsRefusedNamingTheLine) {
  const std::string file = (fs::path(CURIO_TEST_WORK_DIR) / "scenes_bad.csv").string();
  EXPECT_EQ(load_error(std::string(kHeader) + "0,0.1,0.2,0.3,0.4\n1,0.1,0.2,0.3\n"),
            file + ":3: expected 5 comma-separated fields, found 4");
  EXPECT_EQ(load_error(std::string(kHeader) + "0,0.1,0.2,x,0.4\n"),
            file + ":2: field 4 ('x') is not a finite number");
  EXPECT_EQ(load_error(std::string(kHeader) + "0,0.1,0.2,0.3,nan\n"),
            file + ":2: field 5 ('nan') is not a finite number");
  EXPECT_EQ(load_error(std::string(kHeader) + "0,0.1,0.2,0.3,0.4 \n"),
            file + ":2: field 5 ('0.4 ') is not a finite number");
  EXPECT_NE(load_error("episode,ball_x\n0,0.1\n").find(file + ":1: expected the header"),
            std::string::npos);
  EXPECT_EQ(load_error(kHeader), file + ": no scenes after the header");
  EXPECT_THROW(load_scene_set_csv((fs::path(CURIO_TEST_WORK_DIR) / "no_such.csv").string(), 1),
               std::runtime_error);
}

}  // namespace
}  // namespace curio::train
