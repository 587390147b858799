// placeholder
#include <gtest/gtest.h>
TEST(Stripes, Placeholder) {}
