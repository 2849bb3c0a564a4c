// placeholder until the contact-model plugin example lands
