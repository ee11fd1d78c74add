# What the kernel sources are, for the embedded table (cmake/EmbedKernels.cmake) and the hw/ flows' manifests
# (hw/cmake/WriteManifest.cmake) alike, so the host's source hash is the one a board binary's manifest records:
#   rfrecon_kernel_files(VAR KERNEL_DIR)         every .cl and .h file under KERNEL_DIR and the generated
#                                                common/params.h, relative paths, sorted (configure time only)
#   rfrecon_hls_files(VAR KERNEL_DIR)            every .cpp and .h file of the HLS C++ tops, KERNEL_DIR/../hw/hls, as
#                                                "hw/hls/NAME", sorted (configure time only): an HLS binary's sources
#                                                are the kernels' and these
#   rfrecon_kernel_file_path(VAR FILE KERNEL_DIR GENERATED_DIR)   where FILE lies: KERNEL_DIR/../FILE for hw/hls/
#                                                files, else GENERATED_DIR/FILE if it exists, else KERNEL_DIR/FILE
#                                                (GENERATED_DIR is OUT_DIR/kernels of rfrecon_configure_kernel_params)
#   rfrecon_kernel_source_sha256(VAR KERNEL_DIR GENERATED_DIR FILES...)   SHA-256 over "path\n<SHA-256 of the
#                                                file>\n" for every file, in sorted order
#   rfrecon_kernel_names(VAR TEXT)               the names of the __kernel functions TEXT declares
# Usable in script mode (cmake -P) except rfrecon_kernel_files.
function(rfrecon_kernel_files var kernel_dir)
  file(GLOB_RECURSE files CONFIGURE_DEPENDS RELATIVE ${kernel_dir} ${kernel_dir}/*.cl ${kernel_dir}/*.h)
  if("common/params.h" IN_LIST files)
    message(FATAL_ERROR "${kernel_dir}/common/params.h: the parameters header is generated from params.h.in into "
                        "the build tree; remove this copy")
  endif()
  list(APPEND files common/params.h)
  list(SORT files)
  set(${var} ${files} PARENT_SCOPE)
endfunction()

function(rfrecon_hls_files var kernel_dir)
  file(GLOB files CONFIGURE_DEPENDS RELATIVE ${kernel_dir}/.. ${kernel_dir}/../hw/hls/*.cpp ${kernel_dir}/../hw/hls/*.h)
  list(SORT files)
  set(${var} ${files} PARENT_SCOPE)
endfunction()

function(rfrecon_kernel_file_path var file kernel_dir generated_dir)
  if(file MATCHES "^hw/hls/")
    set(${var} ${kernel_dir}/../${file} PARENT_SCOPE)
  elseif(EXISTS ${generated_dir}/${file})
    set(${var} ${generated_dir}/${file} PARENT_SCOPE)
  else()
    set(${var} ${kernel_dir}/${file} PARENT_SCOPE)
  endif()
endfunction()

function(rfrecon_kernel_source_sha256 var kernel_dir generated_dir)
  set(files ${ARGN})
  list(SORT files)
  set(listing "")
  foreach(f IN LISTS files)
    rfrecon_kernel_file_path(path ${f} ${kernel_dir} ${generated_dir})
    file(SHA256 ${path} file_hash)
    string(APPEND listing "${f}\n${file_hash}\n")
  endforeach()
  string(SHA256 hash "${listing}")
  set(${var} ${hash} PARENT_SCOPE)
endfunction()

function(rfrecon_kernel_names var text)
  string(REGEX MATCHALL "__kernel[ \t\n]+void[ \t\n]+[A-Za-z0-9_]+" found "${text}")
  set(names "")
  foreach(declaration IN LISTS found)
    string(REGEX REPLACE ".*[ \t\n]" "" name "${declaration}")
    list(APPEND names ${name})
  endforeach()
  set(${var} ${names} PARENT_SCOPE)
endfunction()
