#include <gtest/gtest.h>
TEST(MeshPlaceholder, ReplacedByMeshWork) { GTEST_SKIP() << "mesh tests are being written"; }
