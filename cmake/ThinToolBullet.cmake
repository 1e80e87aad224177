# Defines the imported target ThinTool::Bullet from Bullet's pkg-config module. Debian's
# BulletConfig.cmake carries relative paths and CMake's FindBullet has no target, so pkg-config
# is the clean way in. Bullet's float and float64 builds differ in btScalar and in ABI: the two
# must never be mixed, hence one switch for the whole build.
function(thintool_find_bullet use_double)
  if(TARGET ThinTool::Bullet)
    return()
  endif()
  find_package(PkgConfig REQUIRED)
  if(use_double)
    set(module bullet-float64)
  else()
    set(module bullet)
  endif()
  pkg_check_modules(THINTOOL_BULLET REQUIRED IMPORTED_TARGET GLOBAL ${module})
  add_library(ThinTool::Bullet INTERFACE IMPORTED GLOBAL)
  target_link_libraries(ThinTool::Bullet INTERFACE PkgConfig::THINTOOL_BULLET)
endfunction()
