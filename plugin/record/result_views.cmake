# result_views: the views that define a warning's outcome and a collision's anticipation
# (result_views.sql), as SQL text with its placeholders filled in, for the driver and
# criticality-campaign alike. No SUMO, no SQLite. Included from the top-level CMakeLists.txt
# before plugin/, whose CMakeLists.txt returns early without SUMO: the campaign tool needs it
# all the same.
set(_crit_views_dir ${CMAKE_CURRENT_LIST_DIR})
set(_crit_views_generated ${PROJECT_BINARY_DIR}/generated/result_views)
# The SQL is embedded at configure time; editing it re-runs CMake.
file(READ ${_crit_views_dir}/result_views.sql CRIT_RESULT_VIEWS_SQL)
if(CRIT_RESULT_VIEWS_SQL MATCHES "\\)crit_views\"")
  message(FATAL_ERROR "result_views.sql must not contain the raw string's end )crit_views\"")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${_crit_views_dir}/result_views.sql)
configure_file(${_crit_views_dir}/result_views_sql.h.in
               ${_crit_views_generated}/result_views_sql.h @ONLY)

add_library(result_views STATIC ${_crit_views_dir}/result_views.cc)
target_include_directories(result_views PUBLIC ${PROJECT_SOURCE_DIR}
                           PRIVATE ${_crit_views_generated})
