# The engine's source hash: SHA-256 of the sorted lines "path sha256(file)" over src/ and
# include/ (and web/simlab_wasm.cc with -DWASM=ON). The builds write it beside what they
# make (POST_BUILD: build/simlab.sources, web/dist/sources.sha256), and the browser and
# WebAssembly tests compare it with the sources' hash now, so a build from other sources
# is caught by content, not by file times.
#
#   cmake -DROOT=REPO [-DWASM=ON] [-DOUT=FILE] -P tools/source_hash.cmake   (no OUT: prints it)
file(GLOB_RECURSE files RELATIVE "${ROOT}" "${ROOT}/src/*.cc" "${ROOT}/src/*.h" "${ROOT}/include/*.h")
if(WASM)
  list(APPEND files web/simlab_wasm.cc)
endif()
list(SORT files)
set(lines "")
foreach(f IN LISTS files)
  file(SHA256 "${ROOT}/${f}" h)
  string(APPEND lines "${f} ${h}\n")
endforeach()
string(SHA256 total "${lines}")
if(OUT)
  file(WRITE "${OUT}" "${total}\n")
else()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E echo "${total}")
endif()
