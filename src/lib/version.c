/* version.c - the library's version string. */
#include "swaywatch/swaywatch.h"

const char *sw_version(void)
{
    return SW_VERSION;
}
