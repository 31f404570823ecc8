/* The library's implementation, compiled once per build configuration into an object that the
 * voxgi tool and the test programs link (they include voxgi.h for the declarations only). */
#define VOXGI_IMPLEMENTATION
#include "../voxgi.h"
