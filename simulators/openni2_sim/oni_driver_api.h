#pragma once
// Debian's OniDriverAPI.h, with the two allocation macros its ONI_EXPORT_DRIVER
// uses from OpenNI's internal XnLib (not shipped in libopenni2-dev).
#ifndef XN_NEW
#define XN_NEW(type, arg) new type(arg)
#endif
#ifndef XN_DELETE
#define XN_DELETE(p) delete (p)
#endif
#include <Driver/OniDriverAPI.h>
