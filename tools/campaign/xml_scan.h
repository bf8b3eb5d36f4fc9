#pragma once
// A small reader for SUMO's XML files (configurations, routes): start tags and their attributes,
// nothing more. Enough to find a .sumocfg's net and route files and the vehicles of a vType;
// comments, processing instructions and CDATA are skipped.
#include <functional>
#include <map>
#include <string>

namespace criticality::campaign {

using XmlAttributes = std::map<std::string, std::string>;

/** Calls `on_tag(name, attributes)` for every start (or empty-element) tag of `text` in document
 *  order. Entities &amp; &lt; &gt; &quot; &apos; in attribute values are decoded. */
void ScanXmlTags(const std::string& text,
                 const std::function<void(const std::string&, const XmlAttributes&)>& on_tag);

}  // namespace criticality::campaign
