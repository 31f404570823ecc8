/* The library's implementation, compiled once per build configuration into an object that the
 * voxgi tool, the examples and the test programs link (they include voxgi.h and voxgi_io.h for
 * the declarations only): voxgi.h's, and voxgi_io.h's mesh loaders. */
#define VOXGI_IMPLEMENTATION
#include "../voxgi.h"
#define VOXGI_IO_IMPLEMENTATION
#include "../voxgi_io.h"
