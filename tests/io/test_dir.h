// The io tests' fixture is the shared one (tests/common/test_support.h).
#pragma once
#include "../common/test_support.h"

using tsrir_test::TempDirTest;
