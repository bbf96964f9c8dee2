/* SPDX-License-Identifier: GPL-3.0-or-later */
/* version.c - the library's version string. */
#include "swaywatch/swaywatch.h"

const char *sw_version(void)
{
    return SW_VERSION;
}
