/* rad — how the library was built. In the source tree this file sets nothing: the
 * build's -D flags and rad_config.h's defaults decide. `make install-lib` installs in
 * its place one generated from the build ($(BUILDDIR)/include/rad/rad_build.h) that
 * records the RAD_INDEX_BITS, RAD_MAX_RES and RAD_MAX_RASTER librad.a was compiled
 * with and the compiler's target (RAD_BUILD_TARGET), so a program built on the
 * installed headers gets the library's layout by default (and RAD_ERR_ABI from
 * rad_init if it overrides RAD_INDEX_BITS). */
#ifndef RAD_BUILD_H
#define RAD_BUILD_H
#endif
