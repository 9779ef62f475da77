// A header that includes itself, twice: 2^64 inclusions without the include-depth limit.
#include "self_include.h"
#include "self_include.h"
