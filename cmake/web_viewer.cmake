# The web viewer's script (--formats html): viewer/viewer.js and three.js, bundled by esbuild
# into one script that libdla holds as text and inlines into every page. three.js and esbuild
# are pinned in viewer/package.json and viewer/package-lock.json and fetched by npm at build
# time (docs/animation.md says why three.js). Without npm, dla3d builds without the viewer and
# --formats html says so.
find_program(DLA_NPM npm)
if(DLA_NPM)
  set(web_viewer_default ON)
else()
  set(web_viewer_default OFF)
  message(STATUS "npm not found: dla3d is built without the web viewer (--formats html)")
endif()
option(DLA_WEB_VIEWER "Build the web viewer (--formats html): npm fetches three.js at build time" ${web_viewer_default})

set(viewer_dir ${PROJECT_BINARY_DIR}/viewer)
set(DLA_VIEWER_SCRIPT_CPP ${PROJECT_BINARY_DIR}/generated/viewer_script.cpp)
if(DLA_WEB_VIEWER)
  if(NOT DLA_NPM)
    message(FATAL_ERROR "DLA_WEB_VIEWER needs npm")
  endif()
  add_custom_command(OUTPUT ${viewer_dir}/npm.stamp
    COMMAND ${CMAKE_COMMAND} -E make_directory ${viewer_dir}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/viewer/package.json
            ${PROJECT_SOURCE_DIR}/viewer/package-lock.json ${viewer_dir}
    COMMAND ${DLA_NPM} ci --prefix ${viewer_dir} --no-audit --no-fund --loglevel=error
    COMMAND ${CMAKE_COMMAND} -E touch ${viewer_dir}/npm.stamp
    DEPENDS ${PROJECT_SOURCE_DIR}/viewer/package.json ${PROJECT_SOURCE_DIR}/viewer/package-lock.json
    COMMENT "Fetching three.js and esbuild for the web viewer (viewer/package-lock.json)"
    VERBATIM)
  # One target runs npm: the viewer (dla_io) and the studio (dla_studio) both bundle with its
  # esbuild, and a rule listed by two targets runs in each at once under make -j, one npm ci
  # deleting the node_modules the other's esbuild runs from (CMake's add_custom_command docs).
  add_custom_target(dla_viewer_npm DEPENDS ${viewer_dir}/npm.stamp)
  add_custom_command(OUTPUT ${viewer_dir}/viewer.bundle.js
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/viewer/viewer.js ${viewer_dir}/viewer.js
    COMMAND ${viewer_dir}/node_modules/.bin/esbuild ${viewer_dir}/viewer.js --bundle --minify --format=iife
            --charset=ascii --legal-comments=eof --log-level=warning --outfile=${viewer_dir}/viewer.bundle.js
    DEPENDS ${PROJECT_SOURCE_DIR}/viewer/viewer.js ${viewer_dir}/npm.stamp
    COMMENT "Bundling the web viewer's script with three.js"
    VERBATIM)
  add_custom_command(OUTPUT ${DLA_VIEWER_SCRIPT_CPP}
    COMMAND ${CMAKE_COMMAND} -DIN=${viewer_dir}/viewer.bundle.js -DOUT=${DLA_VIEWER_SCRIPT_CPP}
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_text.cmake
    DEPENDS ${viewer_dir}/viewer.bundle.js ${PROJECT_SOURCE_DIR}/cmake/embed_text.cmake
    VERBATIM)
else()
  add_custom_command(OUTPUT ${DLA_VIEWER_SCRIPT_CPP}
    COMMAND ${CMAKE_COMMAND} -DOUT=${DLA_VIEWER_SCRIPT_CPP} -P ${PROJECT_SOURCE_DIR}/cmake/embed_text.cmake
    DEPENDS ${PROJECT_SOURCE_DIR}/cmake/embed_text.cmake
    VERBATIM)
endif()

# The growth studio (dla3d studio, docs/studio.md): its server, page and script, with three.js
# bundled the viewer's way, beside dla3d in the build tree and in share/dla3d/studio installed.
# The bust (CGAL's data set) goes with it, for its "The bust" button.
set(studio_dir ${PROJECT_BINARY_DIR}/studio)
set(studio_files ${studio_dir}/server.py ${studio_dir}/index.html)
foreach(file server.py index.html)
  add_custom_command(OUTPUT ${studio_dir}/${file}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/studio/${file} ${studio_dir}/${file}
    DEPENDS ${PROJECT_SOURCE_DIR}/studio/${file}
    VERBATIM)
endforeach()
if(DLA_WEB_VIEWER)
  add_custom_command(OUTPUT ${studio_dir}/studio.js
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/studio/studio.js ${viewer_dir}/studio.js
    COMMAND ${viewer_dir}/node_modules/.bin/esbuild ${viewer_dir}/studio.js --bundle --minify --format=iife
            --charset=ascii --legal-comments=eof --log-level=warning --outfile=${studio_dir}/studio.js
    DEPENDS ${PROJECT_SOURCE_DIR}/studio/studio.js ${viewer_dir}/npm.stamp
    COMMENT "Bundling the studio's script with three.js"
    VERBATIM)
  list(APPEND studio_files ${studio_dir}/studio.js)
endif()
if(EXISTS ${DLA_BUST_OFF})
  add_custom_command(OUTPUT ${studio_dir}/bust.off
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${DLA_BUST_OFF} ${studio_dir}/bust.off
    DEPENDS ${DLA_BUST_OFF}
    VERBATIM)
  list(APPEND studio_files ${studio_dir}/bust.off)
endif()
add_custom_target(dla_studio ALL DEPENDS ${studio_files})
if(DLA_WEB_VIEWER)
  add_dependencies(dla_studio dla_viewer_npm)
endif()
install(FILES ${studio_files} DESTINATION ${CMAKE_INSTALL_DATADIR}/dla3d/studio)
