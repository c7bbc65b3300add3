/* C ABI tests of the version: the header's SPHERA_VERSION_* macros agree with each
 * other and with the library's sphera_version(), and sphera_check_version accepts the
 * header's version and refuses other major and minor versions. */
#include <string.h>

#include "check.h"

int main(void) {
  char expected[64];
  const char *library = sphera_version();
  CHECK(library != NULL);
  /* The string macro is the three numbers. */
  snprintf(expected, sizeof expected, "%u.%u.%u", (unsigned)SPHERA_VERSION_MAJOR,
           (unsigned)SPHERA_VERSION_MINOR, (unsigned)SPHERA_VERSION_PATCH);
  CHECK(strcmp(expected, SPHERA_VERSION_STRING) == 0);
  /* The library reports the header's version, with "+fma" in an FMA build. */
  if (library != NULL) {
    size_t n = strlen(SPHERA_VERSION_STRING);
    printf("header %s, library %s\n", SPHERA_VERSION_STRING, library);
    CHECK(strncmp(library, SPHERA_VERSION_STRING, n) == 0);
    CHECK(strcmp(library + n, sphera_has_hardware_fma() ? "+fma" : "") == 0);
  }
  /* The macros are integer constants usable by the preprocessor. */
#if SPHERA_VERSION_MAJOR < 0 || SPHERA_VERSION_MINOR < 0 || SPHERA_VERSION_PATCH < 0
  CHECK(0);
#endif
  CHECK(sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR));
  CHECK(!sphera_check_version(SPHERA_VERSION_MAJOR + 1u, SPHERA_VERSION_MINOR));
  CHECK(!sphera_check_version(SPHERA_VERSION_MAJOR + 1u, 0u));
  CHECK(!sphera_check_version(UINT32_MAX, SPHERA_VERSION_MINOR));
  /* A header from a later minor release never matches an earlier library. */
  CHECK(!sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR + 1u));
  CHECK(!sphera_check_version(SPHERA_VERSION_MAJOR, UINT32_MAX));
  /* An earlier minor header: refused before 1.0 (minor releases may break), accepted
   * from 1.0 on. */
  if (SPHERA_VERSION_MINOR > 0) {
    CHECK(sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR - 1u) ==
          (SPHERA_VERSION_MAJOR > 0));
  }
  if (SPHERA_VERSION_MAJOR > 0) CHECK(!sphera_check_version(SPHERA_VERSION_MAJOR - 1u, SPHERA_VERSION_MINOR));
  return check_summary();
}
