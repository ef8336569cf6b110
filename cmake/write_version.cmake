# Writes OUT (hydrojump/version.hpp) with five strings:
#   version_string      the project VERSION and, when SRC is a git checkout, the commit it was built
#                       from (`git describe --always --dirty`), e.g. "0.1.0+3399944e07aa-dirty":
#                       provenance, printed in reports and by --version;
#   source_fingerprint  a hash of the program's code only: the content of the files under util/,
#                       cases/, sph/, reference/, compare/, app/, cmake/ and CMakeLists.txt that git tracks or
#                       would track, as they are in the working tree (committed or not). The study
#                       runner's compare stage keys its cache on it;
#   solver_fingerprint  the same over the code that generates and runs the solvers only (all of the
#                       above but compare/ and app/, except app/generate.*, which writes the case
#                       directories): the study's generate, sph and vof stages and
#                       `hydrojump sph --resume` key on it, so a change to the comparator re-runs the
#                       comparison but keeps hours of solver results;
#   sph_fingerprint,    the same over one solver's code: the solver fingerprint's files less reference/
#   vof_fingerprint     (SPH) or less sph/ (VOF). Validation records are keyed on their method's, so a
#                       change to one solver leaves the other's records current.
# Results of other code are never reused, while a commit that touches only documentation, spec files,
# data, tests or scripts keeps them. Without git the four fingerprints are the VERSION.
# Run at every build; the header is rewritten only when its content changes.
cmake_policy(SET CMP0007 NEW)  # script mode: list() keeps empty elements
set(source_id "")
# The four code fingerprints, each named by its variable and hashed from the manifest of the same stem
# (fingerprint <- manifest, solver_fingerprint <- solver_manifest, ...).
set(fingerprint_names fingerprint solver_fingerprint sph_fingerprint vof_fingerprint)
foreach(name IN LISTS fingerprint_names)
  set(${name} "${VERSION}")
endforeach()
if(EXISTS "${SRC}/.git")
  execute_process(COMMAND git -C "${SRC}" describe --always --dirty --abbrev=12
                  OUTPUT_VARIABLE source_id OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    set(source_id "")
  endif()
  # The code: the path and content (SHA1) of every file under these paths that git tracks or would
  # track (untracked but not ignored), as they are in the working tree, leaving out documentation
  # (*.md), spec files (*.toml: each case's own resolved settings are in its fingerprint already) and
  # data (*.csv), so that editing those keeps finished results. Content, not commits: committing a
  # change does not change a fingerprint. Each file is hashed once; the solver manifest is the part
  # of the full one outside compare/ and app/, plus app/generate.*.
  set(code_paths util cases sph reference compare app cmake CMakeLists.txt)
  set(excludes ":(exclude)*.md" ":(exclude)*.toml" ":(exclude)*.csv")
  execute_process(COMMAND git -C "${SRC}" ls-files --cached --others --exclude-standard -- ${code_paths} ${excludes}
                  OUTPUT_VARIABLE listing ERROR_VARIABLE list_error RESULT_VARIABLE list_status)
  string(REPLACE ";" "," listing "${listing}")
  string(REPLACE "\n" ";" files "${listing}")
  list(FILTER files EXCLUDE REGEX "^$")
  list(REMOVE_DUPLICATES files)
  list(SORT files)
  # A path that git does not know (renamed or deleted) would silently drop out of the hash.
  foreach(p IN LISTS code_paths ITEMS app/generate.cpp app/generate.hpp)
    set(known FALSE)
    foreach(f IN LISTS files)
      if(f STREQUAL p OR f MATCHES "^${p}/")
        set(known TRUE)
        break()
      endif()
    endforeach()
    if(NOT known)
      set(list_status 1)
      string(APPEND list_error "${p} is not known to git; ")
    endif()
  endforeach()
  if(list_status EQUAL 0 AND files)
    set(manifest "${VERSION}\n")
    set(solver_manifest "${VERSION}\n")
    set(sph_manifest "${VERSION}\n")
    set(vof_manifest "${VERSION}\n")
    foreach(f IN LISTS files)
      if(EXISTS "${SRC}/${f}")
        file(SHA1 "${SRC}/${f}" h)
      else()
        set(h "deleted")
      endif()
      string(APPEND manifest "${f} ${h}\n")
      if(NOT f MATCHES "^(compare|app)/" OR f MATCHES "^app/generate\\.(cpp|hpp)$")
        string(APPEND solver_manifest "${f} ${h}\n")
        if(NOT f MATCHES "^reference/")
          string(APPEND sph_manifest "${f} ${h}\n")
        endif()
        if(NOT f MATCHES "^sph/")
          string(APPEND vof_manifest "${f} ${h}\n")
        endif()
      endif()
    endforeach()
    foreach(name IN LISTS fingerprint_names)
      string(REPLACE "fingerprint" "manifest" manifest_name "${name}")
      string(SHA1 digest "${${manifest_name}}")
      string(SUBSTRING "${digest}" 0 16 digest)
      set(${name} "${VERSION}+code.${digest}")
    endforeach()
  else()
    # A git failure leaves all four unique to this configure time, so that no cache can match by accident.
    string(TIMESTAMP now "%Y%m%d%H%M%S")
    message(WARNING "write_version: cannot hash ${code_paths} with git (${list_error}); "
                    "the code fingerprints are unique to this build, so no run cache will match them")
    foreach(name IN LISTS fingerprint_names)
      set(${name} "${VERSION}+unhashed.${now}")
    endforeach()
  endif()
endif()
if(source_id)
  set(full_version "${VERSION}+${source_id}")
else()
  set(full_version "${VERSION}")
endif()
file(WRITE "${OUT}.tmp"
  "#pragma once\n"
  "// Generated by cmake/write_version.cmake: the project version, the source commit and the code\n"
  "// fingerprint the run caches are keyed on.\n"
  "namespace hydrojump {\n"
  "inline constexpr const char* version_string = \"${full_version}\";\n"
  "inline constexpr const char* source_fingerprint = \"${fingerprint}\";\n"
  "inline constexpr const char* solver_fingerprint = \"${solver_fingerprint}\";\n"
  "inline constexpr const char* sph_fingerprint = \"${sph_fingerprint}\";\n"
  "inline constexpr const char* vof_fingerprint = \"${vof_fingerprint}\";\n"
  "}\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -E copy_if_different "${OUT}.tmp" "${OUT}")
file(REMOVE "${OUT}.tmp")
