// VKCOLLIDE_API marks what libvkcollide exports: the public API and nothing else. The library
// is compiled with hidden visibility, so a shared libvkcollide exposes no internal symbol an
// engine could bind to by accident (tests/package checks the installed library's exports).
#pragma once

#if defined(_WIN32)
#if defined(VKCOLLIDE_BUILDING_SHARED)
#define VKCOLLIDE_API __declspec(dllexport)
#elif defined(VKCOLLIDE_SHARED)
#define VKCOLLIDE_API __declspec(dllimport)
#else
#define VKCOLLIDE_API
#endif
#else
#define VKCOLLIDE_API __attribute__((visibility("default")))
#endif
