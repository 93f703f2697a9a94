#pragma once
// Internal: the page (src/web/page/index.html, embedded at build time into page_html.cpp).
#include <string_view>

namespace binpick::web::detail {

std::string_view indexHtml();

}  // namespace binpick::web::detail
