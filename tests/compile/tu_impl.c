/* Compile matrix, translation unit 1: the implementation (included twice: the guards hold). */
#define VOXGI_IMPLEMENTATION
#include "../../voxgi.h"
#include "../../voxgi.h"

int tu_impl_version(void) { return VOXGI_VERSION; }
