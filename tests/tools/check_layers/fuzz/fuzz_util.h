// tests/tools/check_layers/fuzz/fuzz_util.h: a folder above every library (not checked, and included by none).
#pragma once
