# Installs a folder's npm packages (pinned by its package-lock.json) with `npm ci`, once: it runs
# again only when the lock file changes (the lock's SHA-256 is kept in node_modules).
#   cmake -DNPM=<npm or empty> -DDIR=<folder with package.json and package-lock.json>
#         [-DREQUIRED=ON] -P NpmCi.cmake
# As a CTest fixture (tests/js, tests/studio): without npm, or when npm ci fails (offline and not
# in npm's cache), it says so and counts as skipped; the tests that need the packages then skip
# too. With REQUIRED (the studio's front end, which the build embeds) either is an error.
function(npm_ci_give_up message)
  if(REQUIRED)
    message(FATAL_ERROR "${message}")
  endif()
  message("npm ci skipped: ${message}")
endfunction()

if(NOT NPM)
  npm_ci_give_up("npm was not found when CMake configured (scripts/install-deps.sh)")
  return()
endif()
file(SHA256 "${DIR}/package-lock.json" lock_hash)
set(stamp "${DIR}/node_modules/.fuzzygait-lock-sha256")
if(EXISTS "${stamp}")
  file(READ "${stamp}" installed_hash)
  if(installed_hash STREQUAL lock_hash)
    message("npm packages already installed in ${DIR}/node_modules (package-lock.json unchanged)")
    return()
  endif()
endif()
string(TIMESTAMP start "%s")
# One quick retry: offline, the default retries would hold every ctest run for over a minute.
execute_process(COMMAND "${NPM}" ci --prefer-offline --no-audit --no-fund --fetch-retries=1
                        --fetch-retry-mintimeout=2000 --fetch-retry-maxtimeout=10000
                WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE result TIMEOUT 300)
string(TIMESTAMP end "%s")
math(EXPR seconds "${end} - ${start}")
if(NOT result EQUAL 0)
  npm_ci_give_up("`npm ci` in ${DIR} failed (${result}) after ${seconds} s; offline?")
  return()
endif()
file(WRITE "${stamp}" "${lock_hash}")
message("npm ci installed the npm packages in ${DIR}/node_modules in ${seconds} s")
