# Run at install time by install(SCRIPT), after the install rules of the
# package's folder (CMakeLists.txt), which sets BOWG_ROS_INSTALLED_DIRS (the
# package's share and include destinations) first.
# In the workspace of scripts/build.sh the package's top-level entries are
# links into the checkout, and install() copies a link as a link:
# catkin_package() installs package.xml from the package folder, i.e. the link,
# and the install space would lead back into the checkout (and break once
# deployed without it). Every link in those destinations that leads out of the
# install prefix is replaced by a copy of its file. (Not from the install
# manifest: install() leaves an unchanged link out of it.) A folder link cannot
# be replaced this way (the next install would fail to put the link back over
# the folder): folders are installed from BOWG_ROS_INSTALL_SOURCE, the checkout.
set(destdir "$ENV{DESTDIR}")
get_filename_component(prefix "${destdir}${CMAKE_INSTALL_PREFIX}" REALPATH)
set(links)
foreach(dir IN LISTS BOWG_ROS_INSTALLED_DIRS)
  if(IS_DIRECTORY "${destdir}${CMAKE_INSTALL_PREFIX}/${dir}")
    file(GLOB_RECURSE entries LIST_DIRECTORIES true "${destdir}${CMAKE_INSTALL_PREFIX}/${dir}/*")
    foreach(entry IN LISTS entries)
      if(IS_SYMLINK "${entry}")
        list(APPEND links "${entry}")
      endif()
    endforeach()
  endif()
endforeach()

foreach(link IN LISTS links)
  get_filename_component(target "${link}" REALPATH)
  string(FIND "${target}/" "${prefix}/" at)
  if(at EQUAL 0)
    continue()
  endif()
  if(IS_DIRECTORY "${target}")
    message(FATAL_ERROR "install: ${link} is a link to the folder ${target}; "
      "install the folder from \${BOWG_ROS_INSTALL_SOURCE} (CMakeLists.txt)")
  endif()
  get_filename_component(parent "${link}" DIRECTORY)
  get_filename_component(name "${link}" NAME)
  get_filename_component(target_name "${target}" NAME)
  if(NOT name STREQUAL target_name)
    # file(COPY) keeps the name: a renaming link is none of the workspace's.
    message(FATAL_ERROR "install: ${link} is a link to ${target}, under another name")
  endif()
  message(STATUS "Installing: ${link} (the file, not the link into the checkout)")
  file(REMOVE "${link}")
  file(COPY "${target}" DESTINATION "${parent}")
endforeach()
