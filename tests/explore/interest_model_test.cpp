#include "firmware/explore/interest_model.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace curio {
namespace {

// Hand-computed with D = 2, W = 10 (SPEC §2.5).
TEST(InterestModel, WorkedExample) {
  auto im = std::make_unique<InterestModel>();
  im->reset(2, 2.0f, 10.0f);
  EXPECT_FLOAT_EQ(im->interest(0), 1e-5f);
  EXPECT_FLOAT_EQ(im->interest(1), 1e-5f);

  // 1) Module 0, g = (0,0), r = (0.3,0.4): c = −0.5, no past goal → p = 0;
  //    cp = 1e-5 + (0 − 1e-5)/10 = 9e-6.
  const float g1[2] = {0, 0}, r1[2] = {0.3f, 0.4f};
  EXPECT_EQ(im->update(0, g1, r1, 2), 0.0f);
  EXPECT_NEAR(im->progress(0), 9e-6, 1e-9);
  EXPECT_NEAR(im->interest(0), 9e-6, 1e-9);

  // 2) g = (1,0), r = (1,0.1): c = −0.1; nearest past goal (0,0) reached (0.3,0.4),
  //    scored against g: c_old = −√0.65 = −0.8062258; p = 0.7062258;
  //    cp = 9e-6 + (0.7062258 − 9e-6)/10 = 0.0706307.
  const float g2[2] = {1, 0}, r2[2] = {1, 0.1f};
  EXPECT_NEAR(im->update(0, g2, r2, 2), 0.7062258, 1e-6);
  EXPECT_NEAR(im->interest(0), 0.0706307, 1e-6);

  // 3) g = (−1,−1), r = (1,1): ‖g−r‖ = 2.83 → c = −D = −2; nearest past goal is (0,0)
  //    (√2 < √5), c_old = −√3.65 = −1.9104973; p = −0.0895027;
  //    cp = 0.0706307 + (−0.0895027 − 0.0706307)/10 = 0.0546174.
  const float g3[2] = {-1, -1}, r3[2] = {1, 1};
  EXPECT_NEAR(im->update(0, g3, r3, 2), -0.0895027, 1e-6);
  EXPECT_NEAR(im->progress(0), 0.0546174, 1e-6);

  // Module 1 has its own history: its first update has p = 0 although module 0 has goals.
  const float g4[2] = {0.1f, 0}, r4[2] = {0.1f, 0};
  EXPECT_EQ(im->update(1, g4, r4, 2), 0.0f);
  EXPECT_NEAR(im->interest(1), 9e-6, 1e-9);
  // 5) Module 1, g = (0,0), r = (1,0): c = −1; nearest past goal of module 1 is (0.1,0)
  //    reached (0.1,0): c_old = −0.1 (module 0's goal (0,0) would give −0.5); p = −0.9;
  //    cp = 9e-6 + (−0.9 − 9e-6)/10 = −0.0899919; interest = |cp|.
  const float g5[2] = {0, 0}, r5[2] = {1, 0};
  EXPECT_NEAR(im->update(1, g5, r5, 2), -0.9, 1e-6);
  EXPECT_NEAR(im->progress(1), -0.0899919, 1e-6);
  EXPECT_NEAR(im->interest(1), 0.0899919, 1e-6);
  EXPECT_NEAR(im->interest(0), 0.0546174, 1e-6);  // untouched
  EXPECT_EQ(im->history().size(), 5);
}

TEST(InterestModel, CompetenceIsCappedAtD) {
  const float g[1] = {0}, near[1] = {0.5f}, far[1] = {3.0f};
  EXPECT_FLOAT_EQ(InterestModel::competence(g, near, 1, 2.0f), -0.5f);
  EXPECT_FLOAT_EQ(InterestModel::competence(g, far, 1, 2.0f), -2.0f);
  EXPECT_FLOAT_EQ(InterestModel::competence(g, far, 1, 1.0f), -1.0f);
  EXPECT_FLOAT_EQ(InterestModel::competence(g, g, 1, 1.0f), 0.0f);
}

TEST(InterestModel, ProgressWithCapOneDiffersFromCapTwo) {
  // Same data, D = 1 (archived EFR runs) vs D = 2: c = −1.5 is capped only by D = 1.
  for (const float cap : {1.0f, 2.0f}) {
    auto im = std::make_unique<InterestModel>();
    im->reset(1, cap, 1000.0f);
    const float g[1] = {0}, r_old[1] = {0.5f}, r_new[1] = {1.5f};
    im->update(0, g, r_old, 1);
    const float p = im->update(0, g, r_new, 1);
    EXPECT_NEAR(p, cap == 1.0f ? -0.5f : -1.0f, 1e-6) << "D = " << cap;
  }
}

TEST(InterestModel, ScaledCompetenceDividesByDAndNeverClips) {
  // explauto's competence_dist as the reference ran it: -|g - r| / dist_max.
  const float g[1] = {0}, near[1] = {0.5f}, far[1] = {3.0f};
  const auto kScaled = CompetenceMeasure::kScaled;
  EXPECT_FLOAT_EQ(InterestModel::competence(g, near, 1, 2.0f, kScaled), -0.25f);
  EXPECT_FLOAT_EQ(InterestModel::competence(g, far, 1, 2.0f, kScaled), -1.5f);
  EXPECT_FLOAT_EQ(InterestModel::competence(g, far, 1, 1.0f, kScaled), -3.0f);
  // Progress under kScaled is the unclipped progress over D: p(D = 2) = p(D = 1) / 2.
  float p_by_cap[2] = {};
  for (int i = 0; i < 2; ++i) {
    auto im = std::make_unique<InterestModel>();
    im->reset(1, i == 0 ? 1.0f : 2.0f, 1000.0f, kScaled);
    const float r_old[1] = {0.5f}, r_new[1] = {3.5f};
    im->update(0, g, r_old, 1);
    p_by_cap[i] = im->update(0, g, r_new, 1);
  }
  EXPECT_NEAR(p_by_cap[0], -3.0f, 1e-6);  // kClipped with D = 1 would give −1 − (−0.5) = −0.5
  EXPECT_NEAR(p_by_cap[1], -1.5f, 1e-6);
}

}  // namespace
}  // namespace curio
