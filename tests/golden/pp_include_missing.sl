// golden: compile
// An #include is searched next to the file, then in the -I directories.
#include "include/nothere.h"
displacement t() {
    P += N;
}
