"""The survey of what urdfdom's XML parser (TinyXML 2.6.2) reads and lxml refuses, or reads
otherwise: one small document per case, run live against check_urdf by test_xmlrecover.

Every case is the same three-link robot with one thing changed. Where check_urdf accepts a
case, ``fishbot check`` must print what it prints; where it refuses, refuse.
"""

from __future__ import annotations

BODY = (
    b'<robot name="r">\n  <link name="a"/>\n  <link name="b"/>\n'
    b'  <joint name="j" type="fixed">\n    <parent link="a"/>\n    <child link="b"/>\n'
    b"  </joint>\n</robot>\n"
)
DECLARATION = b'<?xml version="1.0"?>'


def with_declaration(declaration: bytes) -> bytes:
    return declaration + b"\n" + BODY


def _replace(old: bytes, new: bytes, data: bytes = BODY) -> bytes:
    assert old in data, old
    return data.replace(old, new)


CASES: dict[str, bytes] = {
    "clean": BODY,
    "decl_1.0": with_declaration(b'<?xml version="1.0"?>'),
    "decl_0.0": with_declaration(b'<?xml version="0.0" ?>'),
    "decl_2.0": with_declaration(b'<?xml version="2.0"?>'),
    "decl_1.1": with_declaration(b'<?xml version="1.1"?>'),
    "decl_noversion": with_declaration(b'<?xml encoding="UTF-8"?>'),
    "decl_garbage_version": with_declaration(b'<?xml version="abc"?>'),
    "decl_unquoted": with_declaration(b"<?xml version=1.0?>"),
    "decl_garbage": with_declaration(b"<?xml foo bar ?>"),
    "decl_uppercase": with_declaration(b'<?XML version="1.0"?>'),
    "decl_empty": with_declaration(b"<?xml?>"),
    "decl_after_blank_line": b"\n" + with_declaration(b'<?xml version="1.0"?>'),
    "decl_after_spaces": b"   " + with_declaration(b'<?xml version="1.0"?>'),
    "decl_after_comment": b"<!-- c -->\n" + with_declaration(b'<?xml version="1.0"?>'),
    "decl_twice": with_declaration(b'<?xml version="1.0"?>\n<?xml version="1.0"?>'),
    "decl_after_root": BODY + b'<?xml version="1.0"?>\n',
    "decl_inside_robot": _replace(
        b'  <link name="a"/>', b'  <?xml version="1.0"?>\n  <link name="a"/>'
    ),
    "bom_then_ws": b"\xef\xbb\xbf\n" + with_declaration(b'<?xml version="1.0"?>'),
    "bom": b"\xef\xbb\xbf" + with_declaration(b'<?xml version="1.0"?>'),
    "bom_twice": b"\xef\xbb\xbf\xef\xbb\xbf" + with_declaration(b'<?xml version="1.0"?>'),
    "ws_then_bom": b"\n\xef\xbb\xbf" + with_declaration(b'<?xml version="1.0"?>'),
    "decl_standalone_bad": with_declaration(b'<?xml version="1.0" standalone="maybe"?>'),
    "decl_order_swapped": with_declaration(b'<?xml encoding="UTF-8" version="1.0"?>'),
    "pi_other": with_declaration(b'<?xml-stylesheet href="a.xsl"?>'),
    "pi_before_decl": b"<?foo bar?>\n" + with_declaration(b'<?xml version="1.0"?>'),
    # prefixes
    "prefix_element": _replace(
        b'  <link name="b"/>', b'  <link name="b"/>\n  <drake:joint name="x" type="ball"/>'
    ),
    "prefix_element_in_link": _replace(
        b'<link name="b"/>',
        b'<link name="b"><drake:proximity_properties><drake:mu value="1"/>'
        b"</drake:proximity_properties></link>",
    ),
    "prefix_attribute": _replace(b'<link name="b"/>', b'<link name="b" drake:foo="1"/>'),
    "prefix_attribute_root": _replace(b'<robot name="r">', b'<robot name="r" drake:x="1">'),
    "prefix_on_robot": _replace(b"<robot ", b"<drake:robot ").replace(
        b"</robot>", b"</drake:robot>"
    ),
    "prefix_xmlns_only_value": _replace(b'<robot name="r">', b'<robot name="r" xmlns:drake="">'),
    "prefix_xml_reserved": _replace(b'<link name="b"/>', b'<link name="b" xml:lang="en"/>'),
    "prefix_xmlns_attr": _replace(b'<link name="b"/>', b'<link name="b" xmlns:foo="http://x"/>'),
    "prefix_double_colon": _replace(b'<link name="b"/>', b'<link name="b"><a:b:c/></link>'),
    "prefix_leading_colon": _replace(b'<link name="b"/>', b'<link name="b"><:c/></link>'),
    "prefix_trailing_colon": _replace(b'<link name="b"/>', b'<link name="b"><c:/></link>'),
    "prefix_on_link": _replace(b'<link name="b"/>', b'<x:link name="b"/>'),
    "prefix_on_link_attr_name": _replace(
        b'<link name="b"/>', b'<link name="b"/>\n  <link x:name="c"/>'
    ),
    # encodings
    "latin1_declared_comment": with_declaration(
        b'<?xml version="1.0" encoding="ISO-8859-1"?>'
    ).replace(b"<robot", b"<!-- caf\xe9 -->\n<robot"),
    "latin1_declared_name": with_declaration(
        b'<?xml version="1.0" encoding="ISO-8859-1"?>'
    ).replace(b'"b"', b'"b\xe4"'),
    "latin1_declared_robotname": with_declaration(
        b'<?xml version="1.0" encoding="latin-1"?>'
    ).replace(b'name="r"', b'name="r\xe4"'),
    "latin1_undeclared_comment": with_declaration(b'<?xml version="1.0"?>').replace(
        b"<robot", b"<!-- caf\xe9 -->\n<robot"
    ),
    "latin1_undeclared_name": with_declaration(b'<?xml version="1.0"?>').replace(
        b'"b"', b'"b\xe4"'
    ),
    "latin1_undeclared_material": _replace(
        b'<link name="a"/>',
        b'<link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
        b'<material name="gr\xfcn"><color rgba="0 1 0 1"/></material></visual></link>',
    ),
    "invalid_utf8_comment": _replace(b"<robot", b"<!-- \xff\xfe bad -->\n<robot"),
    "invalid_utf8_text": _replace(
        b'<link name="a"/>', b'<link name="a"><!-- ok -->text \xc3\x28 here</link>'
    ),
    "invalid_utf8_name": _replace(b'"b"', b'"b\xc3\x28"'),
    "invalid_utf8_tag": _replace(b'<link name="a"/>', b'<link name="a"><x\xff/></link>'),
    "utf8_declared_ok": with_declaration(b'<?xml version="1.0" encoding="UTF-8"?>').replace(
        b'"b"', b'"b\xc3\xa4"'
    ),
    "utf8_lower": with_declaration(b'<?xml version="1.0" encoding="utf8"?>'),
    "utf16_bom": with_declaration(b'<?xml version="1.0" encoding="UTF-16"?>')
    .decode()
    .encode("utf-16"),
    "utf16_le_nobom": with_declaration(b'<?xml version="1.0" encoding="UTF-16"?>')
    .decode()
    .encode("utf-16-le"),
    "utf16_be_nobom": with_declaration(b'<?xml version="1.0" encoding="UTF-16"?>')
    .decode()
    .encode("utf-16-be"),
    "encoding_lies_latin1_is_utf8": with_declaration(
        b'<?xml version="1.0" encoding="ISO-8859-1"?>'
    ).replace(b'"b"', b'"b\xc3\xa4"'),
    "encoding_lies_utf8_is_latin1": with_declaration(
        b'<?xml version="1.0" encoding="UTF-8"?>'
    ).replace(b'"b"', b'"b\xe4"'),
    "encoding_unknown": with_declaration(b'<?xml version="1.0" encoding="klingon"?>'),
    "encoding_utf16_but_utf8": with_declaration(b'<?xml version="1.0" encoding="UTF-16"?>'),
    "encoding_ascii_with_utf8": with_declaration(
        b'<?xml version="1.0" encoding="US-ASCII"?>'
    ).replace(b'"b"', b'"b\xc3\xa4"'),
    "cp1252_declared": with_declaration(b'<?xml version="1.0" encoding="windows-1252"?>').replace(
        b"<robot", b"<!-- \x93q\x94 -->\n<robot"
    ),
    # entities
    "amp_stray_text": _replace(b'<link name="a"/>', b'<link name="a">fish & chips</link>'),
    "amp_stray_attr": _replace(
        b'<link name="b"/>',
        b'<link name="b"><visual><geometry><mesh filename="a&b.stl"/></geometry></visual></link>',
    ),
    "amp_in_name": _replace(b'"b"', b'"b&c"'),
    "entity_unknown_attr": _replace(
        b'<link name="b"/>',
        b'<link name="b"><visual><geometry><mesh filename="&foo;.stl"/></geometry></visual></link>',
    ),
    "entity_unknown_name": _replace(b'"b"', b'"b&foo;"'),
    "entity_unknown_robotname": _replace(b'name="r"', b'name="&foo;"'),
    "entity_unknown_text": _replace(b'<link name="a"/>', b'<link name="a">x &foo; y</link>'),
    "entity_amp_noscolon": _replace(b'"b"', b'"b&amp"'),
    "entity_nbsp": _replace(b'"b"', b'"b&nbsp;"'),
    "entity_known": _replace(b'name="r"', b'name="r&amp;&lt;&gt;&quot;&apos;"'),
    "charref_ok": _replace(b'name="r"', b'name="r&#65;&#x42;"'),
    "charref_bad_hex": _replace(b'name="r"', b'name="r&#xZZ;"'),
    "charref_nosemi": _replace(b'name="r"', b'name="r&#65"'),
    "charref_zero": _replace(b'name="r"', b'name="r&#0;x"'),
    "charref_control": _replace(b'name="r"', b'name="r&#1;x"'),
    "charref_huge": _replace(b'name="r"', b'name="r&#x110000;x"'),
    "charref_X_upper": _replace(b'name="r"', b'name="r&#X41;x"'),
    # attribute values
    "lt_in_attr": _replace(
        b'<link name="b"/>',
        b'<link name="b"><visual><geometry><mesh filename="a<b.stl"/></geometry></visual></link>',
    ),
    "lt_in_name": _replace(b'"b"', b'"b<c"'),
    "gt_in_attr": _replace(b'"b"', b'"b>c"'),
    "unquoted_attr": _replace(b'<link name="b"/>', b"<link name=b />"),
    "unquoted_attr_noslash_space": _replace(b'<link name="b"/>', b"<link name=b/>"),
    "unquoted_attr_joint_type": _replace(b'type="fixed"', b"type=fixed"),
    "duplicate_attr": _replace(b'<link name="b"/>', b'<link name="b" name="c"/>'),
    "duplicate_attr_prefixed": _replace(b'<link name="b"/>', b'<link name="b" x:n="1" y:n="2"/>'),
    "attr_no_space": _replace(b'<joint name="j" type="fixed">', b'<joint name="j"type="fixed">'),
    "attr_no_value": _replace(b'<link name="b"/>', b'<link name="b" foo/>'),
    "attr_single_quotes": _replace(b'<link name="b"/>', b"<link name='b'/>"),
    "attr_quote_in_value": _replace(b'<link name="b"/>', b"<link name='b\"c'/>"),
    "attr_ws_around_eq": _replace(b'<link name="b"/>', b'<link name = "b"/>'),
    # content after root
    "after_root_text": BODY + b"trailing text\n",
    "after_root_element": BODY + b"<extra/>\n",
    "after_root_robot": BODY + b'<robot name="second"><link name="z"/></robot>\n',
    "after_root_comment": BODY + b"<!-- end -->\n",
    "after_root_unclosed_comment": BODY + b"<!-- end \n",
    "after_root_garbage_lt": BODY + b"<<<\n",
    "after_root_close_tag": BODY + b"</robot>\n",
    "after_root_broken_element": BODY + b'<foo bar="\n',
    "before_root_element": b"<other/>\n" + BODY,
    "before_root_text": b"hello\n" + BODY,
    "before_root_other_tree": b'<other><robot name="inner"><link name="q"/></robot></other>\n'
    + BODY,
    "only_other_root": b'<other><link name="a"/></other>\n',
    # comments
    "comment_double_dash": _replace(b"<robot", b"<!-- a -- b -->\n<robot"),
    "comment_triple_dash_end": _replace(b"<robot", b"<!-- a --->\n<robot"),
    "comment_unclosed_inside": _replace(b'<link name="a"/>', b'<link name="a"/><!-- oops'),
    "comment_in_tag": _replace(b'<link name="a"/>', b'<link <!-- c --> name="a"/>'),
    "comment_nested": _replace(b"<robot", b"<!-- a <!-- b --> -->\n<robot"),
    # tags
    "end_tag_mismatch": _replace(b"  </joint>", b"  </jiont>"),
    "end_tag_missing": _replace(b"</robot>\n", b""),
    "end_tag_missing_inner": _replace(b"  </joint>\n", b""),
    "end_tag_space": _replace(b"</robot>", b"</robot >"),
    "end_tag_case": _replace(b"</robot>", b"</Robot>"),
    "end_tag_extra": _replace(b'<link name="a"/>', b'<link name="a"/></link>'),
    "tag_space_after_lt": _replace(b'<link name="a"/>', b'< link name="a"/>'),
    "tag_name_digit": _replace(b'<link name="a"/>', b'<link name="a"><1a/></link>'),
    "tag_name_dash_start": _replace(b'<link name="a"/>', b'<link name="a"><-a/></link>'),
    "self_close_space": _replace(b'<link name="a"/>', b'<link name="a" / >'),
    "cdata": _replace(b'<link name="a"/>', b'<link name="a"><![CDATA[ <x> & ]]></link>'),
    "cdata_unclosed": _replace(b'<link name="a"/>', b'<link name="a"><![CDATA[ <x> & </link>'),
    "doctype_plain": b"<!DOCTYPE robot>\n" + BODY,
    "doctype_system": b'<!DOCTYPE robot SYSTEM "urdf.dtd">\n' + BODY,
    "doctype_internal_noent": b"<!DOCTYPE robot [ <!ELEMENT robot ANY> ]>\n" + BODY,
    "doctype_entity": b'<!DOCTYPE robot [ <!ENTITY n "q"> ]>\n'
    + _replace(b'name="r"', b'name="&n;"'),
    "doctype_after_root": BODY + b"<!DOCTYPE robot>\n",
    "doctype_inside": _replace(b'<link name="a"/>', b'<!DOCTYPE x><link name="a"/>'),
    "bang_unknown": _replace(b'<link name="a"/>', b'<!foo bar><link name="a"/>'),
    # raw bytes
    "nul_after_root": BODY + b"\x00garbage<<<",
    "nul_in_comment": _replace(b"<robot", b"<!-- \x00 -->\n<robot"),
    "nul_in_name": _replace(b'"b"', b'"b\x00c"'),
    "control_in_comment": _replace(b"<robot", b"<!-- \x01\x1b -->\n<robot"),
    "control_in_name": _replace(b'"b"', b'"b\x01"'),
    "control_in_text": _replace(b'<link name="a"/>', b'<link name="a">x\x0cy</link>'),
    "del_in_name": _replace(b'"b"', b'"b\x7f"'),
    "cr_only_lines": _replace(b"\n", b"\r"),
    "crlf_lines": _replace(b"\n", b"\r\n"),
    "formfeed_ws": _replace(b"\n  <link", b"\n\x0c<link"),
    "vtab_ws": _replace(b"\n  <link", b"\n\x0b<link"),
    "nbsp_ws_utf8": _replace(b"\n  <link", b"\n\xc2\xa0<link"),
    "empty_file": b"",
    "only_ws": b"  \n",
    "only_decl": b'<?xml version="1.0"?>\n',
    "text_before_decl": b"junk\n" + with_declaration(b'<?xml version="1.0"?>'),
    "noncharacter_bom_like": _replace(b"\n  <link", b"\n\xef\xbf\xbe<link"),
    "robot_uppercase": _replace(b"<robot ", b"<Robot ").replace(b"</robot>", b"</Robot>"),
    "element_name_nonascii": _replace(b'<link name="a"/>', b'<link name="a"><gr\xc3\xbcn/></link>'),
    "attr_name_nonascii": _replace(b'<link name="b"/>', b'<link name="b" gr\xc3\xbcn="1"/>'),
    "ampersand_in_comment": _replace(b"<robot", b"<!-- a & b < c -->\n<robot"),
    "gt_in_text": _replace(b'<link name="a"/>', b'<link name="a">a > b ]]> c</link>'),
}

# Cases lxml reads, but not as urdfdom does (or urdfdom refuses them).
CASES |= {
    "pi_with_gt": b"<?foo a>b?>\n" + BODY,
    "doctype_gt_in_literal": b'<!DOCTYPE robot SYSTEM "a>b">\n' + BODY,
    "doctype_empty_subset": b"<!DOCTYPE robot [ ]>\n" + BODY,
    "doctype_lowercase": b"<!doctype robot>\n" + BODY,
    "doctype_undefined_entity": b'<!DOCTYPE robot SYSTEM "x.dtd">\n'
    + _replace(b'name="r"', b'name="r&foo;"'),
    "charref_228_no_declaration": _replace(b'name="r"', b'name="r&#228;"'),
    "charref_8364_no_declaration": _replace(b'name="r"', b'name="r&#8364;"'),
    "charref_8364_utf8": with_declaration(DECLARATION).replace(b'name="r"', b'name="r&#8364;"'),
    "charref_228_latin1": with_declaration(b'<?xml version="1.0" encoding="ISO-8859-1"?>').replace(
        b'name="r"', b'name="r&#228;"'
    ),
    "stylesheet_before_latin1_declaration": b'<?xml-stylesheet href="x"?>\n'
    + with_declaration(b'<?xml version="1.0" encoding="ISO-8859-1"?>'),
    "unquoted_with_reference": _replace(b'name="r"', b"name=r&amp;x"),
    "pi_inside_element": _replace(b'<link name="a"/>', b'<link name="a"/><?foo bar?>'),
    "latin1_text_swallows_lt": with_declaration(DECLARATION).replace(
        b'<link name="b"/>', b'<link name="b">caf\xe9</link>'
    ),
    "default_namespace": _replace(
        b'<robot name="r">', b'<robot name="r" xmlns="http://example.org/u">'
    ),
    "pi_xml_prefixed_target": b"<?xmlfoo bar?>\n" + BODY,
    "declaration_version_1_5": with_declaration(b'<?xml version="1.5"?>'),
    "after_root_unterminated_tag": BODY + b'<robot name="x" \n',
    "bom_inside_tag": with_declaration(DECLARATION).replace(
        b'<link name="b"', b'<link \xef\xbb\xbfname="b"'
    ),
    "form_feed_after_root": BODY + b"\x0c\n",
    "form_feed_first": b"\x0c" + BODY,
    "cdata_unclosed_after_root": BODY + b"<![CDATA[\n",
    "cdata_after_root": BODY + b"<![CDATA[ x ]]>\n",
}
